#include "pbd/bending_constraint.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace forensim {

double dihedral_angle(const Quad& x) {
  const Vec3 e = x[3] - x[2];
  const Vec3 na = (x[2] - x[0]).cross(x[3] - x[0]);
  const Vec3 nb = (x[3] - x[1]).cross(x[2] - x[1]);
  const double le = e.norm();
  if (na.squaredNorm() <= 0.0 || nb.squaredNorm() <= 0.0 || le <= 0.0) return 0.0;
  return detail::angle_from_normals(na, nb, e, le);
}

double bending_value(const Quad& x, double rest_angle) {
  return detail::wrap_angle(dihedral_angle(x) - rest_angle);
}

BendingConstraints make_bending_constraints(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                                            const std::string& source) {
  struct HalfEdge {
    Index a, b;      // directed edge a -> b of a triangle
    Index opposite;  // the triangle's third vertex
  };
  std::vector<HalfEdge> half;
  half.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Tri& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      require_input(tri[k] >= 0 && static_cast<std::size_t>(tri[k]) < positions.size(), source,
                    "triangle " + std::to_string(t), "has a vertex index out of range");
      half.push_back({tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]});
    }
  }
  // Sort by undirected edge so both half-edges of an edge are neighbours (ties by direction: deterministic).
  auto key = [](const HalfEdge& h) { return std::array<Index, 3>{std::min(h.a, h.b), std::max(h.a, h.b), h.a}; };
  std::sort(half.begin(), half.end(), [&](const HalfEdge& l, const HalfEdge& r) { return key(l) < key(r); });
  BendingConstraints out;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && std::min(half[j].a, half[j].b) == std::min(half[i].a, half[i].b) &&
           std::max(half[j].a, half[j].b) == std::max(half[i].a, half[i].b))
      ++j;
    // Exactly two half-edges in opposite directions: an interior, consistently oriented edge.
    if (j - i == 2 && half[i].a == half[i + 1].b) {
      // Triangle A = (x0, x2, x3) has the directed edge x2 -> x3; B = (x1, x3, x2) has x3 -> x2.
      const HalfEdge& ha = half[i];
      const HalfEdge& hb = half[i + 1];
      const std::array<Index, 4> q{ha.opposite, hb.opposite, ha.a, ha.b};
      const Quad x{positions[static_cast<std::size_t>(q[0])], positions[static_cast<std::size_t>(q[1])],
                   positions[static_cast<std::size_t>(q[2])], positions[static_cast<std::size_t>(q[3])]};
      out.quad_vertices.push_back(q);
      out.rest_angle.push_back(dihedral_angle(x));
    }
    i = j;
  }
  return out;
}

}  // namespace forensim
