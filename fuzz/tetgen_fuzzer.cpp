// Fuzzes the TetGen .node/.ele reader (tet_io/tetgen_io.hpp: parse_tetgen). One input holds both files: the
// .node text, a line "#.ele", then the .ele text (the run script joins the corpus pairs so).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "tet_io/tetgen_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = forensim::fuzz::bytes(data, size);
  constexpr std::string_view separator = "\n#.ele\n";
  const std::size_t at = bytes.find(separator);
  const std::string_view node = bytes.substr(0, at);
  const std::string_view ele = at == std::string_view::npos ? std::string_view() : bytes.substr(at + separator.size());
  try {
    forensim::fuzz::require_valid(forensim::parse_tetgen(node, ele, "fuzz.node", "fuzz.ele"), "parse_tetgen");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
