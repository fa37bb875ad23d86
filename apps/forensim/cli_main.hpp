#pragma once
/// The forensim command line as a function: what the executable's main runs.

namespace forensim::cli {

/// Parses `argv` (argv[0] is the program), runs the subcommand and returns the process's exit code: 0 on
/// success, 2 for a usage error, the error's own code otherwise (core/error.hpp). Installs the crash and
/// interrupt handlers and sets the process-wide thread count, log level and progress style, so it runs once
/// per process.
int run_main(int argc, char** argv);

}  // namespace forensim::cli
