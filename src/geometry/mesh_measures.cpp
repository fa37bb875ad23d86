#include "geometry/mesh_measures.hpp"

#include <cmath>

#include "core/parallel.hpp"

namespace forensim {

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

double surface_area(const TriMesh& mesh) {
  return parallel_sum(0, mesh.triangles.size(), [&](std::size_t f) {
    const Tri& t = mesh.triangles[f];
    return triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  });
}

double enclosed_volume(const TriMesh& mesh) {
  return parallel_sum(0, mesh.triangles.size(), [&](std::size_t f) {
    const Tri& t = mesh.triangles[f];
    return mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]])) / 6.0;
  });
}

double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double tet_mesh_volume(const TetMesh& mesh, int label) {
  return parallel_sum(0, mesh.tets.size(), [&](std::size_t t) {
    if (label >= 0 && mesh.label(t) != label) return 0.0;
    const Tet& k = mesh.tets[t];
    return tet_signed_volume(mesh.positions[k[0]], mesh.positions[k[1]], mesh.positions[k[2]], mesh.positions[k[3]]);
  });
}

std::vector<Vec3> face_normals(const TriMesh& mesh) {
  std::vector<Vec3> normals(mesh.triangles.size());
  parallel_for(0, mesh.triangles.size(), [&](std::size_t f) {
    const Tri& t = mesh.triangles[f];
    const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    const double len = n.norm();
    normals[f] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  });
  return normals;
}

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  // Serial accumulation keeps the result independent of the thread count.
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  const std::vector<Vec3> fn = face_normals(mesh);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = mesh.positions[t[c]];
      const Vec3 e1 = mesh.positions[t[(c + 1) % 3]] - p;
      const Vec3 e2 = mesh.positions[t[(c + 2) % 3]] - p;
      const double denom = e1.norm() * e2.norm();
      if (denom <= 0) continue;
      const double angle = std::acos(std::clamp(e1.dot(e2) / denom, -1.0, 1.0));
      normals[t[c]] += angle * fn[f];
    }
  }
  for (Vec3& n : normals) {
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  return normals;
}

void compute_normals(TriMesh& mesh) {
  mesh.normals = vertex_normals(mesh);
}

}  // namespace forensim
