#include "server/frame_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "geometry/tet_boundary.hpp"
#include "tet_io/vtu_reader.hpp"

namespace forensim {

namespace {
// Rounded to 1 / `scale`, so the JSON stays short (nlohmann prints the shortest round-trip form).
double rounded(double v, double scale) {
  return std::round(v * scale) / scale;
}

// The surface with, per surface vertex, the index of its value in the mesh's vertex fields.
struct Surface {
  TriMesh mesh;
  FieldSet fields;
  std::vector<Index> source_of_vertex;
  const char* cells = "";
};

// A tet volume's boundary, or a triangle mesh as it is. A file whose cells are not tets is read as triangles;
// its error then is the triangle reader's, which got as far as the cells.
Surface read_surface(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  Surface s;
  TetMesh volume;
  bool tets = true;
  try {
    volume = parse_vtu(bytes, path.string());
  } catch (const InputError& e) {
    if (e.problem().find("VTK cell type") == std::string::npos) throw;
    tets = false;
  }
  if (tets) {
    s.mesh = tet_boundary_mesh(volume, -1, nullptr, &s.source_of_vertex);
    s.fields = std::move(volume.vertex_fields);
    s.cells = "tetrahedra";
    return s;
  }
  s.mesh = parse_vtu_surface(bytes, path.string());
  s.fields = std::move(s.mesh.vertex_fields);
  s.source_of_vertex.resize(s.mesh.positions.size());
  for (std::size_t v = 0; v < s.source_of_vertex.size(); ++v) s.source_of_vertex[v] = static_cast<Index>(v);
  s.cells = "triangles";
  return s;
}
}  // namespace

nlohmann::json frame_surface_json(const std::filesystem::path& vtu_path) {
  const Surface s = read_surface(vtu_path);
  const std::size_t n = s.mesh.positions.size();
  const auto source = [&](std::size_t v) { return static_cast<std::size_t>(s.source_of_vertex[v]); };
  nlohmann::json out;
  out["vertex_count"] = n;
  out["triangle_count"] = s.mesh.triangles.size();
  out["cells"] = s.cells;
  std::vector<double> positions(3 * n);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) positions[3 * v + static_cast<std::size_t>(k)] = rounded(s.mesh.positions[v][k], 1e3);
  out["positions"] = positions;
  const auto displacement = s.fields.vectors.find("displacement");
  if (displacement != s.fields.vectors.end()) {
    std::vector<double> rest(3 * n);
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3 r = s.mesh.positions[v] - displacement->second[source(v)];
      for (int k = 0; k < 3; ++k) rest[3 * v + static_cast<std::size_t>(k)] = rounded(r[k], 1e3);
    }
    out["rest_positions"] = rest;
  }
  std::vector<Index> triangles;
  triangles.reserve(3 * s.mesh.triangles.size());
  for (const Tri& t : s.mesh.triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  out["triangles"] = triangles;
  nlohmann::json scalars = nlohmann::json::object(), ranges = nlohmann::json::object();
  for (const auto& [name, values] : s.fields.scalars) {
    std::vector<double> values_out(n);
    double lo = 1e300, hi = -1e300;
    for (std::size_t v = 0; v < n; ++v) {
      const double x = values[source(v)];
      values_out[v] = rounded(x, 1e4);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    scalars[name] = values_out;
    ranges[name] = {n > 0 ? lo : 0.0, n > 0 ? hi : 0.0};
  }
  out["scalars"] = scalars;
  out["ranges"] = ranges;
  nlohmann::json vectors = nlohmann::json::object();
  for (const auto& [name, values] : s.fields.vectors) {
    if (name == "displacement") continue;
    std::vector<double> values_out(3 * n);
    for (std::size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) values_out[3 * v + static_cast<std::size_t>(k)] = rounded(values[source(v)][k], 1e4);
    vectors[name] = values_out;
  }
  out["vectors"] = vectors;
  return out;
}

}  // namespace forensim
