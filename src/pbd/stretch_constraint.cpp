#include "pbd/stretch_constraint.hpp"

#include "core/error.hpp"
#include "geometry/mesh_topology.hpp"

namespace forensim {

double stretch_value(const Vec3& p0, const Vec3& p1, double rest_length) {
  return (p0 - p1).norm() - rest_length;
}

StretchConstraints make_stretch_constraints(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                                            const std::string& source) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (Index v : triangles[t])
      if (v < 0 || static_cast<std::size_t>(v) >= positions.size())
        throw InputError(source, "triangle " + std::to_string(t), "has a vertex index out of range");
  StretchConstraints out;
  out.edge_vertices = unique_edges(triangles);
  out.edge_rest_length.reserve(out.edge_vertices.size());
  for (std::size_t e = 0; e < out.edge_vertices.size(); ++e) {
    const auto& [a, b] = out.edge_vertices[e];
    const double length = (positions[static_cast<std::size_t>(a)] - positions[static_cast<std::size_t>(b)]).norm();
    if (!(length > 0.0))
      throw InputError(source, "edge " + std::to_string(a) + "-" + std::to_string(b),
                       "has zero length (weld the mesh first)");
    out.edge_rest_length.push_back(length);
  }
  return out;
}

}  // namespace forensim
