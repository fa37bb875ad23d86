// forensim serve: the browser viewer and editor. Serves the web front end and a JSON API over the library
// code the CLI uses (runs in the served folder, wound and mummify jobs run in the background, the skull
// editor's in-memory reconstructions), bound to loopback unless --host says otherwise.

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "commands.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "mummify_job.hpp"
#include "server/api_server.hpp"

namespace forensim::cli {
namespace {

struct ServeArgs {
  std::string dir = ".";
  std::string host = "127.0.0.1";
  int port = 8080;
  std::string web;
  int max_jobs = 2;
  int job_threads = 1;
  double max_body_mb = 4.0;
  int max_skull_sessions = 4;
};

std::filesystem::path default_web_dir() {
  if (const char* env = std::getenv("FORENSIM_WEB_DIR"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "forensim" / "web";
    if (std::filesystem::is_regular_file(installed / "index.html", ec)) return installed;
  }
  return FORENSIM_WEB_DIR;
}

int run_serve(const ServeArgs& a) {
  ServerOptions options;
  options.host = a.host;
  options.port = a.port;
  options.served_dir = a.dir;
  options.web_dir = a.web.empty() ? default_web_dir() : std::filesystem::path(a.web);
  std::error_code ec;
  options.executable = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw IoError("/proc/self/exe", "cannot find the forensim executable to run jobs with");
  options.max_running_jobs = a.max_jobs;
  options.threads_per_job = a.job_threads;
  options.max_body_bytes = static_cast<std::size_t>(a.max_body_mb * 1024.0 * 1024.0);
  options.max_skull_sessions = a.max_skull_sessions;
  options.preload_meshes = true;
  if (!std::filesystem::is_regular_file(options.web_dir / "node_modules" / "three" / "build" / "three.module.js")) {
    std::fprintf(stderr,
                 "forensim serve: warning: %s has no node_modules/three (run scripts/install-deps, which runs npm ci "
                 "there); the pages cannot draw without it\n",
                 options.web_dir.string().c_str());
  }
  ApiServer server(options);
  server.jobs().add_kind(mummify_job_kind());
  const int port = server.bind();
  // SIGINT/SIGTERM stop the server (its jobs are cancelled on the way out); a watcher thread polls the flag.
  install_interrupt_handler();
  std::thread watcher([&server] {
    while (!interrupt_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  ::signal(SIGPIPE, SIG_IGN);
  std::printf("forensim serve: http://%s:%d/ (serving %s; Ctrl-C stops)\n",
              a.host.find(':') != std::string::npos ? ("[" + a.host + "]").c_str() : a.host.c_str(), port,
              std::filesystem::absolute(a.dir).string().c_str());
  std::fflush(stdout);
  server.run();
  set_interrupt_requested(true);
  watcher.join();
  return 0;
}

const RegisterCommand serve_command{
    "serve", [](CLI::App& app) {
      auto* sub = app.add_subcommand(
          "serve", "Browser viewer and editor of runs (wound painting, desiccation frames, skull editing)");
      auto a = std::make_shared<ServeArgs>();
      sub->add_option("dir", a->dir, "Folder of runs to serve; new runs are written into it (default: .)");
      sub->add_option("--host", a->host, "Address to listen on (default 127.0.0.1: this machine only)");
      sub->add_option("--port", a->port, "Port (0: any free port, printed at start)")->check(CLI::Range(0, 65535));
      sub->add_option("--web", a->web, "Folder of the front end (default: the one built with forensim)");
      sub->add_option("--max-jobs", a->max_jobs, "Jobs running at once")->check(CLI::Range(1, 64));
      sub->add_option("--job-threads", a->job_threads, "Threads per job")->check(CLI::Range(1, 4096));
      sub->add_option("--max-body-mb", a->max_body_mb, "Largest request body (MiB)")->check(CLI::Range(0.001, 1024.0));
      sub->add_option("--max-skull-sessions", a->max_skull_sessions, "Skull editor sessions held at once")
          ->check(CLI::Range(1, 64));
      return [a]() { return run_serve(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
