#pragma once
/// `forensim serve`'s HTTP server (cpp-httplib): the web front end's files and a JSON API over the library
/// code the CLI uses. Bound to loopback (127.0.0.1) unless another host is given. Every path a request names
/// is resolved inside the served folder or the web folder (served_path.hpp). Errors are JSON
/// {"error": {"status", "message", "field"}}: 400 bad request (with the field at fault), 403 outside the
/// served folder, 404 not found, 409 conflict, 413 body over the limit, 429 too many running jobs.
///
/// Endpoints:
///   GET  /api/health                  version, job kinds, limits
///   GET  /api/runs                    the run folders under the served folder (run_index.hpp)
///   GET  /api/run?path=REL            one run: record, files, timeline or frames
///   GET  /api/files/REL               a file of the served folder, as is
///   GET  /api/frame?path=REL.vtu      a desiccation frame's surface with its fields (frame_surface.hpp)
///   GET  /api/meshes                  built-in meshes; GET /api/meshes/NAME.glb one as GLB
///   GET  /api/jobs                    jobs; POST /api/jobs starts one (job_manager.hpp), 202
///   GET  /api/jobs/ID                 one job; POST /api/jobs/ID/cancel cancels it
///   GET  /api/jobs/ID/events          server-sent events: the job's description on each change, until it ends
///   /api/skull/sessions...            the skull editor's in-memory sessions (skull_sessions.hpp)
///   GET  /...                         files of the web folder ("/" is index.html)

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>

#include "server/job_manager.hpp"

namespace forensim {

class SkullTemplates;

struct ServerOptions {
  std::string host = "127.0.0.1";                     ///< address to bind; loopback unless the user asks otherwise
  int port = 8080;                                    ///< 0: any free port (see ApiServer::port())
  std::filesystem::path served_dir;                   ///< run folders are read from and written into it
  std::filesystem::path web_dir;                      ///< the front end's files (index.html, js/, node_modules/three)
  std::filesystem::path executable;                   ///< the forensim executable that runs jobs
  std::size_t max_body_bytes = std::size_t{4} << 20;  ///< larger request bodies answer 413
  int max_running_jobs = 2;
  int threads_per_job = 1;
  /// Builds the built-in meshes and the skull editor's full template head in the background from the start,
  /// so the wound editor's first load does not wait for the forearm-uv atlas (about 15 s), nor the skull
  /// editor's for the template (about 6 s).
  bool preload_meshes = false;
  int max_skull_sessions = 4;            ///< skull editor sessions at once; more answer 429
  double skull_session_idle_s = 1800.0;  ///< a skull session without a request for this long is forgotten
  /// The skull editor's template heads; null: the server builds its own. Servers in one process (the tests)
  /// can share one, so each template is built once.
  std::shared_ptr<SkullTemplates> skull_templates;
};

class ApiServer {
 public:
  /// Checks the folders (IoError when the served or web folder does not exist) and sets up the routes with the
  /// built-in job kind "wound"; add others with jobs().add_kind().
  explicit ApiServer(ServerOptions options);
  ~ApiServer();
  ApiServer(const ApiServer&) = delete;
  ApiServer& operator=(const ApiServer&) = delete;

  JobManager& jobs();
  /// Binds host:port (port 0: any free one). Throws IoError when it cannot. Returns the port.
  int bind();
  /// Serves until stop() (call bind() first). Blocks.
  void run();
  /// bind() and run() on a background thread; returns the port.
  int start();
  /// Stops serving (from any thread) and joins the background thread of start().
  void stop();
  int port() const;
  const ServerOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// The Content-Type for a file name's extension (application/octet-stream when unknown).
std::string content_type_for(const std::filesystem::path& file);

}  // namespace forensim
