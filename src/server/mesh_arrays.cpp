#include "server/mesh_arrays.hpp"

#include <bit>
#include <cstdint>
#include <cstring>

#include "core/base64.hpp"

namespace forensim {

static_assert(std::endian::native == std::endian::little, "the browser arrays are written in the host's byte order");

std::string positions_float32_base64(const std::vector<Vec3>& positions) {
  std::string bytes(positions.size() * 3 * sizeof(float), '\0');
  char* out = bytes.data();
  for (const Vec3& p : positions) {
    for (int k = 0; k < 3; ++k) {
      const float v = static_cast<float>(p[k]);
      std::memcpy(out, &v, sizeof v);
      out += sizeof v;
    }
  }
  return base64_encode(bytes);
}

std::string triangles_uint32_base64(const std::vector<Tri>& triangles) {
  std::string bytes(triangles.size() * 3 * sizeof(std::uint32_t), '\0');
  char* out = bytes.data();
  for (const Tri& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::uint32_t>(t[k]);
      std::memcpy(out, &v, sizeof v);
      out += sizeof v;
    }
  }
  return base64_encode(bytes);
}

nlohmann::json mesh_arrays_json(const TriMesh& mesh) {
  return {{"vertex_count", mesh.vertex_count()},
          {"triangle_count", mesh.triangle_count()},
          {"positions_f32", positions_float32_base64(mesh.positions)},
          {"triangles_u32", triangles_uint32_base64(mesh.triangles)}};
}

}  // namespace forensim
