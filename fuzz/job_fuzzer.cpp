// Fuzzes the job-file loader (core/job.hpp): JSON parsing with comments, typed and range-checked reads of a
// fixed set of keys (as a run's loader does; fuzz/seeds/job uses them), nested objects and arrays of objects,
// and check_all_used's search for the first unknown key with its "did you mean" suggestion.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/job.hpp"
#include "fuzz_input.hpp"

namespace {

void read_keys(const forensim::JobNode& node) {
  node.get_integer("version", 1, 1, 3);
  node.get<std::string>("name", "run");
  node.get_number("scale", 1.0, 0.0, 1e6);
  node.get<bool>("flag", false);
  node.get_choice("mode", "fast", {"fast", "accurate"});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    forensim::JobDocument job =
        forensim::JobDocument::parse(std::string(forensim::fuzz::bytes(data, size)), "fuzz.json");
    const forensim::JobNode root = job.root();
    read_keys(root);
    const forensim::JobNode environment = root.child("environment");
    read_keys(environment);
    read_keys(environment.child("inner"));
    for (const forensim::JobNode& step : root.children("steps")) {
      read_keys(step);
      if (step.has("steps")) {
        for (const forensim::JobNode& inner : step.children("steps")) read_keys(inner);
      }
    }
    job.check_all_used();
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken or unknown-key job.
  }
  return 0;
}
