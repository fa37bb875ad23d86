#pragma once
/// The skull editor's sessions (skull_session.hpp) of one server: created from a request, found by id,
/// deleted, and forgotten after `idle_seconds` without a request; at most `max_sessions` at once (a session
/// holds a skull, a factored warp and a face: tens of MB). Thread-safe: sessions are shared pointers, so one
/// deleted or expired while a request works on it lives until that request ends.
///
/// Endpoints (wired in api_server.cpp):
///   POST   /api/skull/sessions                 {skull_session_request.hpp} -> 201 the session's description
///   GET    /api/skull/sessions                 {"sessions": [summaries], "limits"}
///   GET    /api/skull/sessions/ID              the description (?geometry=0 leaves out the meshes' triangles)
///   DELETE /api/skull/sessions/ID              {"deleted": ID}
///   POST   /api/skull/sessions/ID/landmarks    {"name", "position"}: move or add one landmark
///   DELETE /api/skull/sessions/ID/landmarks/NAME  remove one landmark (404 when the set has none)
///   GET    /api/skull/sessions/ID/violations   skull/skin violation counts of the current face (?all=1: also
///                                               before the interpolated pairs and the guides)
///   POST   /api/skull/sessions/ID/depths       {"table", "sex", "build"}
///   POST   /api/skull/sessions/ID/guides       {"guides": {...} | null}
///   POST   /api/skull/sessions/ID/expressions  {"name": preset}
///   GET    /api/skull/sessions/ID/skull_landmarks.mrk.json, .../skin_landmarks.mrk.json
///   GET    /api/skull/sessions/ID/head.glb     ?expressions=smile,frown (default smile,frown,surprise; none)
///   POST   /api/skull/sessions/ID/save         {"output": "name", "expressions": [...]}: a run folder, 201

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/skull_session.hpp"
#include "server/skull_templates.hpp"

namespace forensim {

struct SkullSessionLimits {
  int max_sessions = 4;          ///< more answer 429
  double idle_seconds = 1800.0;  ///< a session without a request for this long is forgotten
};

class SkullSessions {
 public:
  SkullSessions(std::filesystem::path served_root, std::shared_ptr<SkullTemplates> templates,
                SkullSessionLimits limits);

  /// Reads the request body `text`, loads the skull and reconstructs. Throws ApiError: 400 for bad JSON or
  /// values (with the field), 403/404 for paths outside the served folder or missing, 429 when max_sessions
  /// exist.
  nlohmann::json create(const std::string& text);
  /// The session `id`; ApiError 404 when there is none (or it expired).
  std::shared_ptr<SkullSession> find(const std::string& id);
  /// Forgets a session; ApiError 404 when there is none.
  nlohmann::json remove(const std::string& id);
  nlohmann::json list();
  const SkullSessionLimits& limits() const { return m_limits; }
  const std::filesystem::path& served_root() const { return m_served; }

 private:
  void expire_locked();

  std::filesystem::path m_served;
  std::shared_ptr<SkullTemplates> m_templates;
  SkullSessionLimits m_limits;
  std::mutex m_mutex;
  std::map<std::string, std::shared_ptr<SkullSession>> m_sessions;
  int m_creating = 0;  ///< sessions being built (they hold a slot)
  std::size_t m_next_id = 1;
};

/// Expression names from a comma-separated query value ("" or absent: smile, frown, surprise; "none": none).
/// Throws ApiError 400 naming "expressions" for an empty name.
std::vector<std::string> expression_list(const std::string& text);

}  // namespace forensim
