#include "geometry/primitives.hpp"

#include <map>

#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"

namespace forensim {

TriMesh make_box_mesh(const Vec3& min, const Vec3& max, int n) {
  n = std::max(n, 1);
  TriMesh mesh;
  // Each face: origin corner and two axes, oriented so that axis_u x axis_v points outward.
  struct Face {
    Vec3 origin, u, v;
  };
  const Vec3 s = max - min;
  const Face faces[6] = {
      {min, Vec3(0, s.y(), 0), Vec3(s.x(), 0, 0)},                              // z = min, normal -z
      {Vec3(min.x(), min.y(), max.z()), Vec3(s.x(), 0, 0), Vec3(0, s.y(), 0)},  // z = max
      {min, Vec3(s.x(), 0, 0), Vec3(0, 0, s.z())},                              // y = min
      {Vec3(min.x(), max.y(), min.z()), Vec3(0, 0, s.z()), Vec3(s.x(), 0, 0)},  // y = max
      {min, Vec3(0, 0, s.z()), Vec3(0, s.y(), 0)},                              // x = min
      {Vec3(max.x(), min.y(), min.z()), Vec3(0, s.y(), 0), Vec3(0, 0, s.z())},  // x = max
  };
  for (const Face& f : faces) {
    const Index base = static_cast<Index>(mesh.positions.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) mesh.positions.push_back(f.origin + f.u * (double(i) / n) + f.v * (double(j) / n));
    }
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const Index a = base + j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({a, d, c});
      }
    }
  }
  // Weld the shared face borders; tolerance well below the grid spacing.
  const double tol = 1e-9 * std::max(1.0, s.norm());
  TriMesh welded = weld_vertices(mesh, tol);
  compute_normals(welded);
  return welded;
}

TriMesh make_icosphere(const Vec3& center, double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& q : p) q.normalize();
  std::vector<Tri> f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<Index, Index>, Index> midpoint;
    auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      p.push_back((p[a] + p[b]).normalized());
      const Index id = static_cast<Index>(p.size() - 1);
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<Tri> next;
    next.reserve(f.size() * 4);
    for (const Tri& tri : f) {
      const Index a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  TriMesh mesh;
  mesh.normals = p;
  for (const Vec3& q : p) mesh.positions.push_back(center + radius * q);
  mesh.triangles = std::move(f);
  return mesh;
}

TetMesh make_box_tet_mesh(const Vec3& min, const Vec3& max, int nx, int ny, int nz) {
  TetMesh mesh;
  nx = std::max(nx, 1);
  ny = std::max(ny, 1);
  nz = std::max(nz, 1);
  auto node = [&](int i, int j, int k) { return static_cast<Index>((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.positions.push_back(
            min + Vec3((max.x() - min.x()) * i / nx, (max.y() - min.y()) * j / ny, (max.z() - min.z()) * k / nz));
      }
    }
  }
  // Kuhn subdivision: the 6 paths from corner 000 to 111 along axis steps.
  static const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (const auto& path : paths) {
          int c[3] = {i, j, k};
          Tet tet;
          tet[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[path[s]];
            tet[s + 1] = node(c[0], c[1], c[2]);
          }
          const Vec3& a = mesh.positions[tet[0]];
          if (tet_signed_volume(a, mesh.positions[tet[1]], mesh.positions[tet[2]], mesh.positions[tet[3]]) < 0) {
            std::swap(tet[2], tet[3]);
          }
          mesh.tets.push_back(tet);
        }
      }
    }
  }
  return mesh;
}

}  // namespace forensim
