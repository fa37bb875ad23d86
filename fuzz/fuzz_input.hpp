#pragma once
/// Helpers shared by the fuzz targets (fuzz/*_fuzzer.cpp): the input as bytes, the input as a file for readers
/// that only take a path, and the check that a reader's accepted result is valid.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

namespace forensim::fuzz {

/// libFuzzer's input as a string_view.
inline std::string_view bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Writes the input to `name` (e.g. "input.nrrd") in a folder of this process's own under the system's temporary
/// folder, removed at exit, and returns its path. Files the input names beside it are looked up in that folder.
std::filesystem::path write_input(std::string_view bytes, const std::string& name);

/// Prints that `reader` accepted an input but returned an invalid result, and aborts: a finding.
[[noreturn]] void report_invalid_result(const char* reader, const char* problem);

/// Aborts (a finding) when a reader returned a result whose validate(source) throws: a reader must reject what
/// it cannot represent validly, not hand it on.
template <typename T>
void require_valid(const T& result, const char* reader) {
  try {
    result.validate(reader);
  } catch (const std::exception& e) {
    report_invalid_result(reader, e.what());
  }
}

}  // namespace forensim::fuzz
