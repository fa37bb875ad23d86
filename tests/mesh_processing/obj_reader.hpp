#pragma once
/// Minimal Wavefront OBJ reader for the tests of mesh_processing and spatial on the shared real scans (the
/// test targets link only their own module, not mesh_io): `v x y z` and `f` records with 1-based or negative
/// indices and optional /vt/vn parts; polygons are fan-triangulated; everything else is ignored.

#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim::test {

inline TriMesh read_obj_positions(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open");
  TriMesh mesh;
  std::string line;
  std::size_t line_number = 0;
  std::vector<Index> face;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      Vec3 p;
      if (!(s >> p.x() >> p.y() >> p.z())) throw InputError(path, "line " + std::to_string(line_number), "bad vertex");
      mesh.positions.push_back(p);
    } else if (tag == "f") {
      face.clear();
      std::string corner;
      while (s >> corner) {
        const long long raw = std::stoll(corner.substr(0, corner.find('/')));
        const long long index = raw < 0 ? static_cast<long long>(mesh.positions.size()) + raw : raw - 1;
        if (index < 0 || index >= static_cast<long long>(mesh.positions.size())) {
          throw InputError(path, "line " + std::to_string(line_number), "vertex index out of range");
        }
        face.push_back(static_cast<Index>(index));
      }
      for (std::size_t k = 1; k + 1 < face.size(); ++k) mesh.triangles.push_back({face[0], face[k], face[k + 1]});
    }
  }
  return mesh;
}

}  // namespace forensim::test
