// forensim's command line: global options, subcommand dispatch and the mapping of library errors to exit
// codes (see core/error.hpp). main.cpp calls run_main; the CLI's tests call it in a forked process.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <map>

#include "cli_main.hpp"
#include "commands.hpp"
#include "core/crash_report.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/run_folder.hpp"

namespace forensim::cli {

std::vector<Command>& command_registry() {
  static std::vector<Command> commands;
  return commands;
}

RegisterCommand::RegisterCommand(std::string name, std::function<std::function<int()>(CLI::App& app)> setup) {
  command_registry().push_back({std::move(name), std::move(setup)});
}

int run_main(int argc, char** argv) {
  install_crash_handler("forensim");
  CLI::App app{
      "forensim: simulates how a body's appearance changes after injury and after death (desiccation,\n"
      "wound healing) and rebuilds a face from a skull (craniofacial reconstruction)."};
  app.set_version_flag("--version", "forensim " + version_string());
  app.require_subcommand(1);
  int threads = 0;
  std::string log_level = "info";
  std::string progress = "auto";
  app.add_option("--threads", threads, "Worker threads (0 = all cores); results do not depend on it")
      ->check(CLI::Range(0, 4096));
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off");
  app.add_option("--progress", progress, "Progress display: auto (bar on a terminal), bar, lines or quiet")
      ->check(CLI::IsMember({"auto", "bar", "lines", "quiet"}));

  std::map<CLI::App*, std::function<int()>> runners;
  for (const auto& command : cli::command_registry()) {
    CLI::App* before = app.get_subcommands({}).empty() ? nullptr : app.get_subcommands({}).back();
    auto runner = command.setup(app);
    CLI::App* sub = app.get_subcommands({}).back();
    if (sub != before) runners[sub] = std::move(runner);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : static_cast<int>(ErrorKind::usage);
  }

  try {
    set_log_level(log_level);
    set_thread_count(threads);
    set_progress_style(progress == "bar"     ? ProgressStyle::bar
                       : progress == "lines" ? ProgressStyle::lines
                       : progress == "quiet" ? ProgressStyle::quiet
                                             : ProgressStyle::automatic);
    install_interrupt_handler();
    for (CLI::App* sub : app.get_subcommands()) {
      auto it = runners.find(sub);
      if (it != runners.end()) {
        const CrashActivity activity("forensim " + sub->get_name());
        return it->second();
      }
    }
    std::fprintf(stderr, "forensim: error: no subcommand given (see forensim --help)\n");
    return static_cast<int>(ErrorKind::usage);
  } catch (const Error& e) {
    std::fprintf(stderr, "forensim: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "forensim: error: out of memory (the input may be too large for this machine)\n");
    return static_cast<int>(ErrorKind::generic);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "forensim: error: %s\n", e.what());
    return static_cast<int>(ErrorKind::generic);
  }
}

}  // namespace forensim::cli
