#include "server/api_server.hpp"

#include <atomic>
#include <chrono>
#include <system_error>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/run_folder.hpp"
#include "server/api_error.hpp"
#include "server/builtin_meshes.hpp"
#include "server/frame_surface.hpp"
#include "server/run_index.hpp"
#include "server/served_path.hpp"
#include "server/skull_session_request.hpp"
#include "server/skull_sessions.hpp"
#include "server/wound_job_kind.hpp"

// Last: <resolv.h>, which httplib.h includes, defines the macro _res, a parameter name in Eigen's headers.
#include <httplib.h>

namespace forensim {
namespace fs = std::filesystem;

std::string content_type_for(const fs::path& file) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".json", "application/json"},
      {".map", "application/json"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},
      {".svg", "image/svg+xml"},
      {".glb", "model/gltf-binary"},
      {".gltf", "model/gltf+json"},
      {".vtu", "application/xml"},
      {".pvd", "application/xml"},
      {".csv", "text/csv; charset=utf-8"},
      {".txt", "text/plain; charset=utf-8"},
      {".md", "text/plain; charset=utf-8"},
      {".exr", "image/x-exr"},
      {".wasm", "application/wasm"},
  };
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

namespace {

constexpr std::size_t kMaxServedFileBytes = std::size_t{1} << 30;

const char* status_title(int status) {
  switch (status) {
    case 400:
      return "bad request";
    case 403:
      return "forbidden";
    case 404:
      return "not found";
    case 405:
      return "method not allowed";
    case 409:
      return "conflict";
    case 413:
      return "request body too large";
    case 429:
      return "too many jobs";
    default:
      return status >= 500 ? "server error" : "error";
  }
}

void send_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

// The skull editor's answers and the frames of a run carry meshes (base64 float arrays, hundreds of kB that barely
// compress). cpp-httplib 0.11 compresses "application/json" with brotli at its highest quality when the browser accepts
// it, which took 0.76 s for a 13.5k-vertex face (gzip 13 ms, none 1 ms, on loopback); it leaves this exact
// type with its charset alone.
void send_mesh_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json; charset=utf-8");
}

void send_error(httplib::Response& res, int status, const std::string& message, const std::string& field = {}) {
  send_json(res, status, {{"error", {{"status", status}, {"message", message}, {"field", field}}}});
}

// Maps the library's errors onto statuses.
void send_exception(httplib::Response& res, std::exception_ptr ep) {
  try {
    std::rethrow_exception(ep);
  } catch (const ApiError& e) {
    send_error(res, e.status(), e.what(), e.field());
  } catch (const JobError& e) {
    send_error(res, 400, e.what(), e.key_path());
  } catch (const InputError& e) {
    send_error(res, 400, e.what());
  } catch (const IoError& e) {
    send_error(res, 404, e.what());
  } catch (const std::exception& e) {
    send_error(res, 500, e.what());
  } catch (...) {
    send_error(res, 500, "unknown error");
  }
}

// A served path, or the ApiError that answers it.
fs::path require_path(const fs::path& root, const std::string& relative, const std::string& field) {
  const ServedPath p = resolve_served_path(root, relative);
  switch (p.problem) {
    case ServedPathProblem::none:
      return p.path;
    case ServedPathProblem::malformed:
      throw ApiError(400, p.message, field);
    case ServedPathProblem::outside:
      throw ApiError(403, p.message, field);
    case ServedPathProblem::missing:
      throw ApiError(404, p.message, field);
  }
  throw ApiError(500, "unreachable");
}

std::string query(const httplib::Request& req, const std::string& name) {
  if (!req.has_param(name.c_str())) throw ApiError(400, "query parameter '" + name + "' is missing", name);
  return req.get_param_value(name.c_str());
}

void send_file(httplib::Response& res, const fs::path& file, const std::string& relative) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw ApiError(404, "path '" + relative + "' is a folder, not a file");
  if (!fs::is_regular_file(file, ec)) throw ApiError(404, "path '" + relative + "' is not a regular file");
  res.status = 200;
  res.set_content(read_file(file, kMaxServedFileBytes), content_type_for(file).c_str());
  res.set_header("Cache-Control", "no-cache");
}

}  // namespace

struct ApiServer::Impl {
  ServerOptions options;
  fs::path served, web;
  httplib::Server http;
  std::shared_ptr<BuiltinMeshes> meshes = std::make_shared<BuiltinMeshes>();
  std::unique_ptr<JobManager> jobs;
  std::shared_ptr<SkullTemplates> templates;
  std::unique_ptr<SkullSessions> skull_sessions;
  std::thread thread;
  int port = -1;
  std::thread preload;
  std::atomic<bool> stopping{false};  ///< ends event streams, so stop() does not wait for running jobs

  void routes();
  template <typename Get, typename Post, typename Delete>
  void skull_routes(const Get& get, const Post& post, const Delete& del);
  void handle(const httplib::Request& req, httplib::Response& res,
              const std::function<void(const httplib::Request&, httplib::Response&)>& body) {
    try {
      body(req, res);
    } catch (...) {
      send_exception(res, std::current_exception());
    }
  }
};

// The skull editor (skull_sessions.hpp).
template <typename Get, typename Post, typename Delete>
void ApiServer::Impl::skull_routes(const Get& get, const Post& post, const Delete& del) {
  using Req = httplib::Request;
  using Res = httplib::Response;
  const std::string base = "/api/skull/sessions";
  const std::string one = base + "/([^/]+)";
  post(base, [this](const Req& req, Res& res) { send_mesh_json(res, 201, skull_sessions->create(req.body)); });
  get(base, [this](const Req&, Res& res) { send_mesh_json(res, 200, skull_sessions->list()); });
  get(one, [this](const Req& req, Res& res) {
    const bool geometry = !req.has_param("geometry") || req.get_param_value("geometry") != "0";
    send_mesh_json(res, 200, skull_sessions->find(req.matches[1])->describe(geometry));
  });
  del(one, [this](const Req& req, Res& res) { send_mesh_json(res, 200, skull_sessions->remove(req.matches[1])); });
  post(one + "/landmarks", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    JobDocument doc = parse_request(req.body, "landmark edit");
    const LandmarkEdit edit = read_landmark_edit(doc.root());
    doc.check_all_used();
    send_mesh_json(res, 200, session->move_landmark(edit));
  });
  del(one + "/landmarks/([^/]+)", [this](const Req& req, Res& res) {
    send_mesh_json(res, 200, skull_sessions->find(req.matches[1])->remove_landmark(req.matches[2]));
  });
  get(one + "/violations", [this](const Req& req, Res& res) {
    const bool all = req.has_param("all") && req.get_param_value("all") == "1";
    send_mesh_json(res, 200, skull_sessions->find(req.matches[1])->violations(all));
  });
  post(one + "/depths", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    JobDocument doc = parse_request(req.body, "tissue depths");
    const SkullDepthChoice choice = read_depth_choice(doc.root(), served);
    doc.check_all_used();
    send_mesh_json(res, 200, session->set_depths(choice));
  });
  post(one + "/guides", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    JobDocument doc = parse_request(req.body, "guides");
    const std::optional<FaceGuides> guides = read_guides_request(doc.root());
    doc.check_all_used();
    send_mesh_json(res, 200, session->set_guides(guides));
  });
  post(one + "/expressions", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    JobDocument doc = parse_request(req.body, "expression");
    const std::string name = doc.root().require<std::string>("name");
    doc.check_all_used();
    send_mesh_json(res, 200, session->expression(name));
  });
  get(one + R"(/(skull|skin)_landmarks\.mrk\.json)", [this](const Req& req, Res& res) {
    const std::string which = req.matches[2];
    res.status = 200;
    res.set_content(skull_sessions->find(req.matches[1])->markups(which), "application/json");
    res.set_header("Content-Disposition", "attachment; filename=\"" + which + "_landmarks.mrk.json\"");
  });
  get(one + R"(/head\.glb)", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    const auto expressions = expression_list(req.has_param("expressions") ? req.get_param_value("expressions") : "");
    res.status = 200;
    res.set_content(session->glb(expressions), "model/gltf-binary");
    res.set_header("Content-Disposition", "attachment; filename=\"head.glb\"");
  });
  post(one + "/save", [this](const Req& req, Res& res) {
    auto session = skull_sessions->find(req.matches[1]);
    JobDocument doc = parse_request(req.body, "save");
    const std::string output = doc.root().require<std::string>("output");
    const auto names = doc.root().get<std::vector<std::string>>("expressions", {"smile", "frown", "surprise"});
    doc.check_all_used();
    if (!valid_output_name(output)) {
      throw ApiError(400, "output folder name '" + output + "' must be 1 to 64 letters, digits, '.', '_' or '-'",
                     "/output");
    }
    const ServedPath target = resolve_served_path(served, output, false);
    if (target.problem != ServedPathProblem::none) throw ApiError(400, target.message, "/output");
    std::error_code ec;
    if (fs::exists(fs::symlink_status(target.path, ec))) {
      throw ApiError(409, "output folder '" + output + "' exists already; choose another name", "/output");
    }
    nlohmann::json j = session->save(target.path, names);
    j["output"] = output;
    send_mesh_json(res, 201, j);
  });
}

void ApiServer::Impl::routes() {
  using Req = httplib::Request;
  using Res = httplib::Response;
  auto get = [this](const std::string& pattern, std::function<void(const Req&, Res&)> body) {
    http.Get(pattern, [this, body](const Req& req, Res& res) { handle(req, res, body); });
  };
  auto post = [this](const std::string& pattern, std::function<void(const Req&, Res&)> body) {
    http.Post(pattern, [this, body](const Req& req, Res& res) { handle(req, res, body); });
  };
  auto del = [this](const std::string& pattern, std::function<void(const Req&, Res&)> body) {
    http.Delete(pattern, [this, body](const Req& req, Res& res) { handle(req, res, body); });
  };

  get("/api/health", [this](const Req&, Res& res) {
    send_json(res, 200,
              {{"forensim_version", version_string()},
               {"served_folder", served.filename().string()},
               {"job_kinds", jobs->kind_names()},
               {"builtin_meshes", BuiltinMeshes::names()},
               {"limits",
                {{"max_body_bytes", options.max_body_bytes},
                 {"max_running_jobs", options.max_running_jobs},
                 {"max_skull_sessions", options.max_skull_sessions},
                 {"skull_session_idle_s", options.skull_session_idle_s}}},
               {"running_jobs", jobs->running_count()}});
  });
  get("/api/runs", [this](const Req&, Res& res) { send_json(res, 200, list_runs(served)); });
  get("/api/run", [this](const Req& req, Res& res) {
    const std::string relative = req.has_param("path") ? req.get_param_value("path") : "";
    const fs::path folder = require_path(served, relative, "path");
    if (!fs::is_regular_file(folder / "run.json")) {
      throw ApiError(404, "path '" + relative + "' is not a run folder (no run.json)", "path");
    }
    send_json(res, 200, describe_run(served, folder));
  });
  get(R"(/api/files/(.*))", [this](const Req& req, Res& res) {
    const std::string relative = req.matches[1].str();
    send_file(res, require_path(served, relative, "path"), relative);
  });
  get("/api/frame", [this](const Req& req, Res& res) {
    const std::string relative = query(req, "path");
    const fs::path file = require_path(served, relative, "path");
    if (file.extension() != ".vtu") throw ApiError(400, "path '" + relative + "' is not a .vtu frame", "path");
    send_mesh_json(res, 200, frame_surface_json(file));
  });
  get("/api/meshes", [](const Req&, Res& res) { send_json(res, 200, {{"meshes", BuiltinMeshes::names()}}); });
  get(R"(/api/meshes/([^/]+)\.glb)", [this](const Req& req, Res& res) {
    const std::string name = req.matches[1].str();
    if (!BuiltinMeshes::known(name)) throw ApiError(404, "no built-in mesh '" + name + "'");
    res.status = 200;
    res.set_content(meshes->glb(name), "model/gltf-binary");
  });
  get("/api/jobs", [this](const Req&, Res& res) { send_json(res, 200, {{"jobs", jobs->list()}}); });
  post("/api/jobs", [this](const Req& req, Res& res) { send_json(res, 202, jobs->start(req.body)); });
  get(R"(/api/jobs/([^/]+))", [this](const Req& req, Res& res) { send_json(res, 200, jobs->get(req.matches[1])); });
  post(R"(/api/jobs/([^/]+)/cancel)",
       [this](const Req& req, Res& res) { send_json(res, 200, jobs->cancel(req.matches[1])); });
  get(R"(/api/jobs/([^/]+)/events)", [this](const Req& req, Res& res) {
    const std::string id = req.matches[1];
    jobs->get(id);  // 404 before the stream starts
    auto last = std::make_shared<std::string>();
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider("text/event-stream", [this, id, last](std::size_t, httplib::DataSink& sink) {
      if (stopping) {
        sink.done();
        return true;
      }
      nlohmann::json j;
      try {
        jobs->wait(id, last->empty() ? 0.0 : 0.5);
        j = jobs->get(id);
      } catch (const ApiError&) {
        sink.done();
        return true;
      }
      const std::string text = j.dump();
      if (text != *last) {
        const std::string event = "data: " + text + "\n\n";
        if (!sink.write(event.data(), event.size())) return false;
        *last = text;
      }
      if (j["state"] != "running") sink.done();
      return true;
    });
  });
  skull_routes(get, post, del);
  get(R"(/api/.*)", [](const Req& req, Res&) { throw ApiError(404, "no endpoint " + req.path); });
  post(R"(/.*)", [](const Req& req, Res&) { throw ApiError(404, "no endpoint " + req.path); });
  get(R"(/(.*))", [this](const Req& req, Res& res) {
    std::string relative = req.matches[1].str();
    if (relative.empty() || relative.back() == '/') relative += "index.html";
    send_file(res, require_path(web, relative, "path"), relative);
  });
}

ApiServer::ApiServer(ServerOptions options) : m_impl(std::make_unique<Impl>()) {
  Impl& m = *m_impl;
  m.options = std::move(options);
  std::error_code ec;
  m.served = fs::canonical(m.options.served_dir, ec);
  if (ec || !fs::is_directory(m.served)) throw IoError(m.options.served_dir.string(), "served folder does not exist");
  m.web = fs::canonical(m.options.web_dir, ec);
  if (ec || !fs::is_regular_file(m.web / "index.html")) {
    throw IoError(m.options.web_dir.string(), "web folder does not exist or has no index.html");
  }
  JobManagerOptions jo;
  jo.executable = m.options.executable;
  jo.served_root = m.served;
  jo.max_running = m.options.max_running_jobs;
  jo.threads_per_job = m.options.threads_per_job;
  m.jobs = std::make_unique<JobManager>(jo);
  m.jobs->add_kind(wound_job_kind(m.meshes));
  m.templates = m.options.skull_templates ? m.options.skull_templates : std::make_shared<SkullTemplates>();
  SkullSessionLimits limits;
  limits.max_sessions = m.options.max_skull_sessions;
  limits.idle_seconds = m.options.skull_session_idle_s;
  m.skull_sessions = std::make_unique<SkullSessions>(m.served, m.templates, limits);
  m.http.set_payload_max_length(m.options.max_body_bytes);
  m.http.set_keep_alive_timeout(2);
  // Errors httplib answers itself (413 over the limit, 404 without a route) get the same JSON body.
  m.http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) {
      std::string message = status_title(res.status);
      if (res.status == 413) message = "request body is larger than the server's limit";
      send_error(res, res.status, message);
    }
  });
  m.http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) { send_exception(res, ep); });
  m.routes();
  if (m.options.preload_meshes) {
    m.preload = std::thread([meshes = m.meshes, templates = m.templates] {
      for (const std::string& name : BuiltinMeshes::names()) {
        try {
          meshes->glb(name);
        } catch (const std::exception&) {  // answered again (with the error) when a request asks for it
        }
      }
      try {
        templates->get("full");
      } catch (const std::exception&) {
      }
    });
  }
}

ApiServer::~ApiServer() {
  stop();
  if (m_impl->preload.joinable()) m_impl->preload.join();
  m_impl->jobs.reset();
  m_impl->skull_sessions.reset();
}

JobManager& ApiServer::jobs() {
  return *m_impl->jobs;
}

int ApiServer::bind() {
  Impl& m = *m_impl;
  if (m.options.port == 0) {
    m.port = m.http.bind_to_any_port(m.options.host);
  } else {
    m.port = m.http.bind_to_port(m.options.host, m.options.port) ? m.options.port : -1;
  }
  if (m.port <= 0) {
    throw IoError(m.options.host + ":" + std::to_string(m.options.port),
                  "cannot listen there (address in use, or not an address of this machine)");
  }
  return m.port;
}

void ApiServer::run() {
  m_impl->http.listen_after_bind();
}

int ApiServer::start() {
  const int p = bind();
  auto ended = std::make_shared<std::atomic<bool>>(false);
  m_impl->thread = std::thread([this, ended] {
    run();
    *ended = true;
  });
  // stop() is only heard once the server is listening.
  while (!m_impl->http.is_running() && !*ended) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return p;
}

void ApiServer::stop() {
  m_impl->stopping = true;
  m_impl->http.stop();
  if (m_impl->thread.joinable()) m_impl->thread.join();
}

int ApiServer::port() const {
  return m_impl->port;
}

const ServerOptions& ApiServer::options() const {
  return m_impl->options;
}

}  // namespace forensim
