#include "server/skull_sessions.hpp"

#include <algorithm>
#include <cstdio>
#include <random>

#include "core/error.hpp"
#include "craniofacial/face_expression.hpp"
#include "server/api_error.hpp"

namespace forensim {

SkullSessions::SkullSessions(std::filesystem::path served_root, std::shared_ptr<SkullTemplates> templates,
                             SkullSessionLimits limits)
    : m_served(std::move(served_root)), m_templates(std::move(templates)), m_limits(limits) {}

void SkullSessions::expire_locked() {
  for (auto it = m_sessions.begin(); it != m_sessions.end();) {
    it = it->second->idle_seconds() > m_limits.idle_seconds ? m_sessions.erase(it) : std::next(it);
  }
}

nlohmann::json SkullSessions::create(const std::string& text) {
  JobDocument doc = parse_request(text, "skull session request");
  const SkullSessionRequest request = read_skull_session_request(doc.root(), m_served);
  doc.check_all_used();
  std::string id;
  {
    std::lock_guard lock(m_mutex);
    expire_locked();
    if (static_cast<int>(m_sessions.size()) + m_creating >= m_limits.max_sessions) {
      throw ApiError(429, "the server holds " + std::to_string(m_limits.max_sessions) +
                              " skull sessions already; delete one (DELETE /api/skull/sessions/ID) or wait until one "
                              "expires");
    }
    ++m_creating;
    // Ids that are hard to guess: a counter and random digits.
    std::random_device device;
    // (Formatted into a buffer: GCC 12 warns falsely (-Wrestrict) on string concatenation here.)
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "s%zu-%06u", m_next_id++, static_cast<unsigned>(device() % 1000000u));
    id = buffer;
  }
  std::shared_ptr<SkullSession> session;
  try {
    std::shared_ptr<const TemplateHead> head = m_templates->get(request.template_detail);
    session = std::make_shared<SkullSession>(id, std::move(head), request);
  } catch (...) {
    std::lock_guard lock(m_mutex);
    --m_creating;
    throw;
  }
  {
    std::lock_guard lock(m_mutex);
    --m_creating;
    m_sessions[id] = session;
  }
  return session->describe(true);
}

std::shared_ptr<SkullSession> SkullSessions::find(const std::string& id) {
  std::lock_guard lock(m_mutex);
  expire_locked();
  const auto it = m_sessions.find(id);
  if (it == m_sessions.end()) {
    throw ApiError(404,
                   "no skull session '" + id + "' (it may have expired after " +
                       std::to_string(static_cast<long long>(m_limits.idle_seconds)) + " s without a request)",
                   "id");
  }
  return it->second;
}

nlohmann::json SkullSessions::remove(const std::string& id) {
  std::lock_guard lock(m_mutex);
  if (m_sessions.erase(id) == 0) throw ApiError(404, "no skull session '" + id + "'", "id");
  return {{"deleted", id}};
}

nlohmann::json SkullSessions::list() {
  std::vector<std::shared_ptr<SkullSession>> sessions;
  {
    std::lock_guard lock(m_mutex);
    expire_locked();
    for (const auto& [id, s] : m_sessions) sessions.push_back(s);
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& s : sessions) list.push_back(s->summary());
  return {{"sessions", list},
          {"limits", {{"max_sessions", m_limits.max_sessions}, {"idle_seconds", m_limits.idle_seconds}}}};
}

std::vector<std::string> expression_list(const std::string& text) {
  if (text.empty()) return {"smile", "frown", "surprise"};
  try {
    return parse_expression_list(text, "expressions");
  } catch (const InputError& e) {
    throw ApiError(400, e.problem() + " in '" + text + "'", "expressions");
  }
}

}  // namespace forensim
