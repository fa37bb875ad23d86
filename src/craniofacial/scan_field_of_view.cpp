#include "craniofacial/scan_field_of_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace forensim {

ScanFieldOfView ScanFieldOfView::of_volume(const ScalarGrid& grid) {
  grid.validate("field of view volume");
  ScanFieldOfView f;
  f.m_bounded = true;
  f.m_origin = grid.origin;
  f.m_world_to_index = grid.index_to_world_matrix().inverse();
  f.m_direction = grid.direction;
  for (int a = 0; a < 3; ++a) f.m_direction.col(a).normalize();
  f.m_spacing = grid.spacing;
  f.m_last = Vec3(grid.nx - 1, grid.ny - 1, grid.nz - 1);
  return f;
}

double ScanFieldOfView::depth_mm(const Vec3& point) const {
  if (!m_bounded) return std::numeric_limits<double>::infinity();
  const Vec3 u = m_world_to_index * (point - m_origin);
  double depth = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) depth = std::min({depth, u[a] * m_spacing[a], (m_last[a] - u[a]) * m_spacing[a]});
  return depth;
}

bool ScanFieldOfView::contains(const Vec3& point, double margin_mm) const {
  return !m_bounded || depth_mm(point) >= margin_mm;
}

std::vector<char> ScanFieldOfView::cap_triangles(const TriMesh& surface) const {
  std::vector<char> cap(surface.triangles.size(), 0);
  if (!m_bounded) return cap;
  std::vector<Vec3> index(surface.positions.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = m_world_to_index * (surface.positions[i] - m_origin);
  constexpr double slab = 0.25;  // samples: the cap lies between the last sample and the padding
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const Tri& f = surface.triangles[t];
    const Vec3& a = surface.positions[f[0]];
    const Vec3 n = (surface.positions[f[1]] - a).cross(surface.positions[f[2]] - a);
    const double len = n.norm();
    if (len == 0.0) continue;
    for (int axis = 0; axis < 3 && !cap[t]; ++axis) {
      for (int side = 0; side < 2 && !cap[t]; ++side) {
        bool on_face = true;
        for (int k = 0; k < 3 && on_face; ++k) {
          const double u = index[f[k]][axis];
          on_face = side == 0 ? u <= slab : u >= m_last[axis] - slab;
        }
        const double outward = (side == 0 ? -1.0 : 1.0) * n.dot(m_direction.col(axis)) / len;
        if (on_face && outward > 0.7) cap[t] = 1;
      }
    }
  }
  return cap;
}

}  // namespace forensim
