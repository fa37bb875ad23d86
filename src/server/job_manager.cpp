#include "server/job_manager.hpp"

#include <system_error>

#include "core/error.hpp"
#include "server/api_error.hpp"
#include "server/served_path.hpp"

namespace forensim {
namespace fs = std::filesystem;

bool valid_output_name(const std::string& name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  for (const char c : name) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

JobManager::JobManager(JobManagerOptions options) : m_options(std::move(options)) {}

JobManager::~JobManager() {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(m_mutex);
    jobs = m_jobs;
  }
  for (const auto& job : jobs) job->process->cancel(1.0);
  for (const auto& job : jobs) job->process->wait_for(5.0);
}

void JobManager::add_kind(JobKind kind) {
  std::lock_guard lock(m_mutex);
  const std::string name = kind.name;
  m_kinds[name] = std::move(kind);
}

std::vector<std::string> JobManager::kind_names() const {
  std::lock_guard lock(m_mutex);
  std::vector<std::string> names;
  for (const auto& [name, kind] : m_kinds) names.push_back(name);
  return names;
}

int JobManager::running_count() const {
  std::lock_guard lock(m_mutex);
  int n = 0;
  for (const auto& job : m_jobs) n += job->process->snapshot().state == ProcessState::running ? 1 : 0;
  return n;
}

nlohmann::json JobManager::start(const std::string& text) {
  nlohmann::json body;
  try {
    body = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw ApiError(400, "request body is not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    throw ApiError(400, std::string("request body is not valid JSON: ") + e.what());
  }
  if (!body.is_object()) throw ApiError(400, "request body must be a JSON object");
  JobDocument doc = JobDocument::parse(text, "request");
  const JobNode root = doc.root();
  JobKind kind;
  std::string output;
  std::size_t id_number = 0;
  try {
    root.get_integer("version", 1, 1, 1);
    const std::string kind_name = root.require<std::string>("kind");
    {
      std::lock_guard lock(m_mutex);
      const auto it = m_kinds.find(kind_name);
      if (it == m_kinds.end()) {
        std::string known;
        for (const auto& [name, k] : m_kinds) known += (known.empty() ? "" : ", ") + name;
        throw ApiError(400, "unknown job kind '" + kind_name + "' (known: " + known + ")", "/kind");
      }
      kind = it->second;
      id_number = m_next_id++;
    }
    output = root.get<std::string>("output", kind_name + "-" + std::to_string(id_number));
  } catch (const JobError& e) {
    throw ApiError(400, e.what(), e.key_path());
  }
  if (!valid_output_name(output)) {
    throw ApiError(400, "output folder name '" + output + "' must be 1 to 64 letters, digits, '.', '_' or '-'",
                   "/output");
  }
  const ServedPath target = resolve_served_path(m_options.served_root, output, false);
  if (target.problem != ServedPathProblem::none) throw ApiError(400, target.message, "/output");
  std::error_code ec;
  if (fs::exists(fs::symlink_status(target.path, ec))) {
    throw ApiError(409, "output folder '" + output + "' exists already; choose another name", "/output");
  }
  {
    std::lock_guard lock(m_mutex);
    int running = 0;
    for (const auto& job : m_jobs) running += job->process->snapshot().state == ProcessState::running ? 1 : 0;
    if (running + m_starting >= m_options.max_running) {
      throw ApiError(429, std::to_string(running + m_starting) + " jobs are running (the limit is " +
                              std::to_string(m_options.max_running) + "); wait for one or cancel it");
    }
    ++m_starting;
  }
  // The slot is held while the kind prepares (which may load a mesh) and until the process runs.
  struct Release {
    JobManager* m;
    ~Release() {
      if (m == nullptr) return;
      std::lock_guard lock(m->m_mutex);
      --m->m_starting;
    }
  } release{this};
  fs::create_directories(target.path, ec);
  if (ec) throw ApiError(500, "cannot create output folder '" + output + "': " + ec.message(), "/output");
  const JobContext context{fs::canonical(m_options.served_root), target.path, output, body};
  PreparedJob prepared;
  try {
    prepared = kind.prepare(root, context);
    doc.check_all_used();
  } catch (...) {
    fs::remove_all(target.path, ec);
    try {
      throw;
    } catch (const JobError& e) {
      throw ApiError(400, e.what(), e.key_path());
    } catch (const InputError& e) {
      throw ApiError(400, e.what());
    } catch (const IoError& e) {
      throw ApiError(400, e.what());
    }
  }
  std::vector<std::string> arguments = {"--progress", "lines", "--threads", std::to_string(m_options.threads_per_job)};
  arguments.insert(arguments.end(), prepared.arguments.begin(), prepared.arguments.end());
  auto job = std::make_shared<Job>();
  job->id = "job-" + std::to_string(id_number);
  job->kind = kind.name;
  job->output = output;
  job->summary = prepared.summary;
  try {
    job->process = std::make_unique<JobProcess>(m_options.executable, arguments, context.served_root);
  } catch (const Error& e) {
    throw ApiError(500, e.what());
  }
  std::lock_guard lock(m_mutex);
  m_jobs.push_back(job);
  --m_starting;
  release.m = nullptr;
  // Forget the oldest finished jobs beyond max_kept.
  for (auto it = m_jobs.begin(); m_jobs.size() > m_options.max_kept && it != m_jobs.end();) {
    if ((*it)->process->snapshot().state != ProcessState::running) {
      it = m_jobs.erase(it);
    } else {
      ++it;
    }
  }
  return describe(*job);
}

std::shared_ptr<JobManager::Job> JobManager::find(const std::string& id) const {
  std::lock_guard lock(m_mutex);
  for (const auto& job : m_jobs)
    if (job->id == id) return job;
  throw ApiError(404, "no job '" + id + "'");
}

nlohmann::json JobManager::describe(const Job& job) {
  const ProcessSnapshot s = job.process->snapshot();
  static const char* const names[] = {"running", "succeeded", "failed", "cancelled"};
  nlohmann::json j;
  j["id"] = job.id;
  j["kind"] = job.kind;
  j["output"] = job.output;
  j["state"] = names[static_cast<int>(s.state)];
  if (s.progress) {
    const double fraction =
        s.progress->total > 0 ? static_cast<double>(s.progress->done) / static_cast<double>(s.progress->total) : 0.0;
    j["progress"] = {{"label", s.progress->label},
                     {"done", s.progress->done},
                     {"total", s.progress->total},
                     {"fraction", s.state == ProcessState::succeeded ? 1.0 : fraction}};
  } else {
    j["progress"] = {{"fraction", s.state == ProcessState::succeeded ? 1.0 : 0.0}};
  }
  j["exit_code"] = s.state == ProcessState::running ? nlohmann::json(nullptr) : nlohmann::json(s.exit_code);
  j["error"] = s.error;
  j["seconds"] = s.seconds;
  j["log"] = s.last_lines;
  j["summary"] = job.summary;
  return j;
}

nlohmann::json JobManager::get(const std::string& id) const {
  return describe(*find(id));
}

nlohmann::json JobManager::list() const {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(m_mutex);
    jobs = m_jobs;
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& job : jobs) out.push_back(describe(*job));
  return out;
}

nlohmann::json JobManager::cancel(const std::string& id) {
  const auto job = find(id);
  if (job->process->snapshot().state != ProcessState::running) {
    throw ApiError(409, "job '" + id + "' has already ended");
  }
  job->process->cancel();
  return describe(*job);
}

bool JobManager::wait(const std::string& id, double seconds) const {
  return find(id)->process->wait_for(seconds);
}

}  // namespace forensim
