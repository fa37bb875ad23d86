#pragma once
/// A `forensim mummify` run as a function, for the command and for the demo report.

#include <string>
#include <vector>

#include "mummify_job.hpp"

namespace forensim::cli {

/// Runs the desiccation of the body and its skin and writes the run folder `a.out` (see cmd_mummify.cpp).
/// Returns 0; throws the project's errors.
int run_mummify(const MummifyArgs& a);

}  // namespace forensim::cli
