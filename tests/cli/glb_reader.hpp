#pragma once
/// A minimal GLB reader for the CLI tests: the JSON chunk as nlohmann::json and float accessors from the
/// binary chunk (glTF 2.0 binary container: 12-byte header, then JSON and BIN chunks).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace forensim::test {

struct Glb {
  nlohmann::json json;
  std::string bin;

  /// Float values of accessor `index` (tightly packed, as forensim writes them).
  std::vector<float> floats(int index) const {
    const nlohmann::json& accessor = json.at("accessors").at(static_cast<std::size_t>(index));
    EXPECT_EQ(accessor.at("componentType").get<int>(), 5126);
    const std::string type = accessor.at("type");
    const std::size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    const nlohmann::json& view = json.at("bufferViews").at(accessor.at("bufferView").get<std::size_t>());
    const std::size_t offset = view.value("byteOffset", std::size_t{0}) + accessor.value("byteOffset", std::size_t{0});
    std::vector<float> values(accessor.at("count").get<std::size_t>() * components);
    if (offset + values.size() * sizeof(float) > bin.size()) {
      ADD_FAILURE() << "accessor " << index << " outside the binary chunk";
      return {};
    }
    std::memcpy(values.data(), bin.data() + offset, values.size() * sizeof(float));
    return values;
  }
};

/// Parses GLB bytes; fails the test (and returns an empty json) when the container is malformed.
inline Glb parse_glb(const std::string& bytes) {
  Glb glb;
  auto word = [&](std::size_t at) {
    std::uint32_t w = 0;
    if (at + 4 <= bytes.size()) std::memcpy(&w, bytes.data() + at, 4);
    return w;
  };
  if (bytes.size() < 20 || word(0) != 0x46546C67u || word(4) != 2 || word(8) != bytes.size() ||
      word(16) != 0x4E4F534Au) {
    ADD_FAILURE() << "not a GLB 2.0 file";
    return glb;
  }
  const std::size_t json_length = word(12);
  glb.json = nlohmann::json::parse(bytes.substr(20, json_length));
  const std::size_t bin_at = 20 + json_length;
  if (bin_at + 8 <= bytes.size() && word(bin_at + 4) == 0x004E4942u) glb.bin = bytes.substr(bin_at + 8, word(bin_at));
  return glb;
}

}  // namespace forensim::test
