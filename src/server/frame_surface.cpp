#include "server/frame_surface.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/tet_boundary.hpp"
#include "tet_io/vtu_reader.hpp"

namespace forensim {

namespace {
// Rounded to `digits` decimals, so the JSON stays short (nlohmann prints the shortest round-trip form).
double rounded(double v, double scale) {
  return std::round(v * scale) / scale;
}
}  // namespace

nlohmann::json frame_surface_json(const std::filesystem::path& vtu_path) {
  const TetMesh volume = read_vtu(vtu_path);
  std::vector<Index> node_of_vertex;
  const TriMesh surface = tet_boundary_mesh(volume, -1, nullptr, &node_of_vertex);
  const std::size_t n = surface.positions.size();
  nlohmann::json out;
  out["vertex_count"] = n;
  out["triangle_count"] = surface.triangles.size();
  std::vector<double> positions(3 * n), rest(3 * n);
  const auto displacement = volume.vertex_fields.vectors.find("displacement");
  for (std::size_t v = 0; v < n; ++v) {
    const auto node = static_cast<std::size_t>(node_of_vertex[v]);
    Vec3 r = surface.positions[v];
    if (displacement != volume.vertex_fields.vectors.end()) r -= displacement->second[node];
    for (int k = 0; k < 3; ++k) {
      positions[3 * v + static_cast<std::size_t>(k)] = rounded(surface.positions[v][k], 1e3);
      rest[3 * v + static_cast<std::size_t>(k)] = rounded(r[k], 1e3);
    }
  }
  out["positions"] = positions;
  out["rest_positions"] = rest;
  std::vector<Index> triangles;
  triangles.reserve(3 * surface.triangles.size());
  for (const Tri& t : surface.triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  out["triangles"] = triangles;
  nlohmann::json scalars = nlohmann::json::object(), ranges = nlohmann::json::object();
  for (const auto& [name, values] : volume.vertex_fields.scalars) {
    std::vector<double> s(n);
    double lo = 1e300, hi = -1e300;
    for (std::size_t v = 0; v < n; ++v) {
      const double x = values[static_cast<std::size_t>(node_of_vertex[v])];
      s[v] = rounded(x, 1e4);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    scalars[name] = s;
    ranges[name] = {n > 0 ? lo : 0.0, n > 0 ? hi : 0.0};
  }
  out["scalars"] = scalars;
  out["ranges"] = ranges;
  return out;
}

}  // namespace forensim
