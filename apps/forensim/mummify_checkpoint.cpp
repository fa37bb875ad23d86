#include "mummify_checkpoint.hpp"

#include <cstdint>
#include <cstring>

#include "core/atomic_file.hpp"
#include "core/byte_record.hpp"
#include "core/error.hpp"

namespace forensim::cli {
namespace {

constexpr char magic[8] = {'F', 'S', 'M', 'U', 'M', 'M', 'Y', '1'};

void put_section(std::string& out, const std::string& section) {
  bytes::append(out, static_cast<std::uint64_t>(section.size()));
  out += section;
}

std::string get_section(const std::string& in, std::size_t& offset, const std::string& source, const char* what) {
  require_input(in.size() - offset >= sizeof(std::uint64_t), source, "byte " + std::to_string(offset),
                std::string("ends before the ") + what + " section");
  const auto n = bytes::read<std::uint64_t>(in, offset);
  require_input(n <= in.size() - offset, source, "byte " + std::to_string(offset),
                std::string("the ") + what + " section runs past the end of the file");
  std::string section = in.substr(offset, static_cast<std::size_t>(n));
  offset += static_cast<std::size_t>(n);
  return section;
}

}  // namespace

void write_mummify_checkpoint(const std::filesystem::path& path, const DesiccationState& state,
                              const std::vector<std::string>& skins) {
  std::string out(magic, 8);
  bytes::append(out, static_cast<std::uint64_t>(skins.size()));
  put_section(out, desiccation_checkpoint_bytes(state));
  for (const std::string& skin : skins) put_section(out, skin);
  write_file_atomic(path, out);
}

MummifyCheckpoint read_mummify_checkpoint(const std::filesystem::path& path, std::size_t vertex_count) {
  const std::string source = path.string();
  const std::string in = read_file(path);
  require_input(in.size() >= 8 && std::memcmp(in.data(), magic, 8) == 0, source, "byte 0",
                "not a forensim mummify checkpoint");
  require_input(in.size() >= 16, source, "byte 8", "ends before the number of skins");
  std::size_t offset = 8;
  const auto count = bytes::read<std::uint64_t>(in, offset);
  require_input(count <= 64, source, "byte 8", "implausible number of skins " + std::to_string(count));
  MummifyCheckpoint out;
  out.state = desiccation_state_from_bytes(get_section(in, offset, source, "desiccation"), vertex_count,
                                           source + " (desiccation)");
  for (std::uint64_t k = 0; k < count; ++k) out.skins.push_back(get_section(in, offset, source, "skin"));
  require_input(offset == in.size(), source, "byte " + std::to_string(offset), "unexpected bytes after the skin");
  return out;
}

}  // namespace forensim::cli
