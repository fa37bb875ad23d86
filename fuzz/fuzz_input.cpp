#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include "core/error.hpp"
#include "core/log.hpp"

namespace forensim::fuzz {
namespace {

// This process's scratch folder; the destructor runs at libFuzzer's normal exit (-max_total_time, -runs).
struct ScratchFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("forensim_fuzz_" + std::to_string(::getpid()));
  ScratchFolder() { std::filesystem::create_directories(path); }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

std::filesystem::path write_input(std::string_view bytes, const std::string& name) {
  static const ScratchFolder folder;
  const std::filesystem::path path = folder.path / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void report_invalid_result(const char* reader, const char* problem) {
  std::fprintf(stderr, "fuzz: %s accepted the input but returned an invalid result: %s\n", reader, problem);
  std::abort();
}

}  // namespace forensim::fuzz

// Readers log warnings about odd but accepted inputs; at tens of thousands of inputs a second that is noise.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  forensim::set_log_level("off");
  return 0;
}
