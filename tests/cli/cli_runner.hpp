#pragma once
/// Runs the forensim executable from tests and captures its exit code and output.

#include <sys/wait.h>
#include <cstdio>
#include <string>

namespace forensim::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `forensim <arguments>` through the shell (arguments are passed as written).
inline CliResult run_cli(const std::string& arguments) {
  const std::string command = std::string(FORENSIM_CLI_PATH) + " --progress quiet " + arguments + " 2>&1";
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace forensim::test
