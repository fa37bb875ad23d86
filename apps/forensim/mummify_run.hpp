#pragma once
/// A `forensim mummify` run as a function, for the command and for the demo report.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace forensim::cli {

/// The command's options. Without a job file every value comes from here; with one, the job's values win
/// except for options given on the command line (`sub`, null when called from code: nothing counts as given).
struct MummifyArgs {
  std::string job, phantom = "arm", size = "small", model, out = "out/mummify";
  double days = 21.0, step_hours = 12.0, temperature = 35.0, humidity = 30.0, wind = 1.0;
  int frames = 6, picture_size = 480, map_size = 512;
  std::vector<double> gravity;
  double contact_mm = 3.0;
  bool resume = false, no_pictures = false;
  CLI::App* sub = nullptr;
  bool given(const std::string& option) const;
};

/// Runs the desiccation of the body and its skin and writes the run folder `a.out` (see cmd_mummify.cpp).
/// Returns 0; throws the project's errors.
int run_mummify(const MummifyArgs& a);

}  // namespace forensim::cli
