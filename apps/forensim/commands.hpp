#pragma once
/// The forensim CLI's subcommands. Each lives in its own cmd_<name>.cpp and registers itself on the app;
/// its callback parses into a job (the same loader the server and tests use) and runs library code.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace forensim::cli {

/// A subcommand: `setup` adds it (with its options) to the app; the returned function runs it after
/// parsing and returns the exit code.
struct Command {
  std::string name;
  std::function<std::function<int()>(CLI::App& app)> setup;
};

/// Every subcommand, in the order --help lists them.
std::vector<Command>& command_registry();

/// Adds a command to the registry at static-initialisation time.
struct RegisterCommand {
  RegisterCommand(std::string name, std::function<std::function<int()>(CLI::App& app)> setup);
};

}  // namespace forensim::cli
