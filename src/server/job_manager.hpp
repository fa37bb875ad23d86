#pragma once
/// The background jobs of `forensim serve`. A request names a job kind ("wound", "mummify") and an output
/// folder; the kind reads the request through the same job loaders the CLI uses (so it is validated before
/// anything runs, and a bad value is answered with the JSON pointer of the field at fault), writes the job
/// file into the output folder and returns the CLI arguments that run it; the manager then runs the forensim
/// executable as a child process (see job_process.hpp) and reports its progress until it ends or is
/// cancelled. At most `max_running` jobs run at once.
///
/// A request (version 1):
///   {"kind": "wound", "output": "my-wound", ... kind options ..., "job": { the kind's job file }}
/// Keys the kind does not read are errors (core/job.hpp's check_all_used), anywhere in the request.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/job.hpp"
#include "server/job_process.hpp"

namespace forensim {

/// Where a job runs: the served folder and the job's output folder inside it (created, empty).
struct JobContext {
  std::filesystem::path served_root;    ///< resolved served folder
  std::filesystem::path output_folder;  ///< resolved output folder (exists)
  std::string output;                   ///< output folder relative to the served folder
  nlohmann::json request;               ///< the parsed request body (for copying its "job" verbatim)
};

/// What a kind prepared: the arguments after the executable's name, and a summary shown with the job.
struct PreparedJob {
  std::vector<std::string> arguments;
  nlohmann::json summary = nlohmann::json::object();
};

/// A job kind. `prepare` reads `request` (the whole request; its job file under request.child("job")),
/// throws JobError/InputError/ApiError for bad input, writes what the run needs into context.output_folder
/// and returns the arguments. It does not call check_all_used (the manager does, after it).
struct JobKind {
  std::string name;
  std::function<PreparedJob(const JobNode& request, const JobContext& context)> prepare;
};

struct JobManagerOptions {
  std::filesystem::path executable;   ///< the forensim executable that runs jobs
  std::filesystem::path served_root;  ///< outputs go into folders under it
  int max_running = 2;                ///< jobs running at once; more answer 429
  int threads_per_job = 1;            ///< --threads of each job (results do not depend on it)
  std::size_t max_kept = 64;          ///< finished jobs remembered (the oldest are forgotten)
};

class JobManager {
 public:
  explicit JobManager(JobManagerOptions options);
  /// Cancels every running job and waits for them.
  ~JobManager();
  JobManager(const JobManager&) = delete;
  JobManager& operator=(const JobManager&) = delete;

  void add_kind(JobKind kind);
  std::vector<std::string> kind_names() const;

  /// Validates and starts a job from the request body `text`. Returns the job's description (see get()).
  /// Throws ApiError: 400 for bad JSON or values (with the field), 409 when the output folder exists, 429
  /// when max_running jobs are running, 500 when the process cannot start.
  nlohmann::json start(const std::string& text);
  /// {"id", "kind", "output", "state": "running"|"succeeded"|"failed"|"cancelled", "progress": {"label",
  ///  "done", "total", "fraction"}, "exit_code", "error", "seconds", "log": [last lines], "summary"}.
  /// Throws ApiError 404 for an unknown id.
  nlohmann::json get(const std::string& id) const;
  /// Every remembered job, oldest first.
  nlohmann::json list() const;
  /// Asks a running job to stop; returns its description. 404 for an unknown id, 409 when it has ended.
  nlohmann::json cancel(const std::string& id);
  /// Waits until the job has ended or `seconds` passed; true when it ended. 404 for an unknown id.
  bool wait(const std::string& id, double seconds) const;
  int running_count() const;

 private:
  struct Job {
    std::string id, kind, output;
    nlohmann::json summary;
    std::unique_ptr<JobProcess> process;
  };
  std::shared_ptr<Job> find(const std::string& id) const;
  static nlohmann::json describe(const Job& job);

  JobManagerOptions m_options;
  std::map<std::string, JobKind> m_kinds;
  mutable std::mutex m_mutex;
  std::vector<std::shared_ptr<Job>> m_jobs;
  std::size_t m_next_id = 1;
  int m_starting = 0;  ///< jobs being prepared (they hold a slot of max_running)
};

/// Whether `name` is an acceptable output folder name: 1 to 64 of [A-Za-z0-9._-], not starting with '.'.
bool valid_output_name(const std::string& name);

}  // namespace forensim
