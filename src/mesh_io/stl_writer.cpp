#include "mesh_io/stl_writer.hpp"

#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

void append_float(std::string& out, double value) {
  const float f = static_cast<float>(value);
  char bytes[4];
  std::memcpy(bytes, &f, 4);  // x86/ARM little-endian hosts, as STL requires
  out.append(bytes, 4);
}

}  // namespace

void write_stl(const std::filesystem::path& path, const TriMesh& mesh) {
  mesh.validate("mesh written to " + path.string());
  require_input(mesh.triangles.size() <= std::numeric_limits<std::uint32_t>::max(), path.string(), "",
                "too many triangles for STL");
  std::string out(80, ' ');
  out.replace(0, 32, "forensim binary STL, millimetres");
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((count >> (8 * b)) & 0xFF));
  out.reserve(84 + 50 * mesh.triangles.size());
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.positions[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.positions[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.positions[static_cast<std::size_t>(t[2])];
    Vec3 n = (b - a).cross(c - a);
    const double length = n.norm();
    n = length > 0.0 ? Vec3(n / length) : Vec3::Zero();
    for (const Vec3* p : std::initializer_list<const Vec3*>{&n, &a, &b, &c}) {
      for (int k = 0; k < 3; ++k) append_float(out, (*p)[k]);
    }
    out.append(2, '\0');
  }
  write_file_atomic(path, out);
}

}  // namespace forensim
