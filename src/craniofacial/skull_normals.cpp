#include "craniofacial/skull_normals.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

struct SkullSurface::Impl {
  TriMesh mesh;
  ClosestPointQuery query;
  std::vector<Vec3> face_normal;
  std::vector<double> face_area;
  std::vector<Index> adjacency_offsets;  // CSR: neighbours of triangle t are adjacency[offsets[t] .. offsets[t+1])
  std::vector<Index> adjacency;
  explicit Impl(const TriMesh& m) : mesh(m), query(m) {}
};

namespace {

/// Area of the part of triangle (a, b, c) within `radius` of `center`, from a 4 x 4 barycentric subdivision
/// (16 sub-triangles, each counted whole when its centroid is inside).
double area_inside_ball(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& center, double radius, double area) {
  constexpr int n = 4;
  const double r2 = radius * radius;
  int inside = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n - i; ++j) {
      // Upward sub-triangle (i, j), (i+1, j), (i, j+1) and, when it exists, the downward one.
      const double u = (i + 1.0 / 3.0) / n, v = (j + 1.0 / 3.0) / n;
      if (((1.0 - u - v) * a + u * b + v * c - center).squaredNorm() <= r2) ++inside;
      if (i + j < n - 1) {
        const double u2 = (i + 2.0 / 3.0) / n, v2 = (j + 2.0 / 3.0) / n;
        if (((1.0 - u2 - v2) * a + u2 * b + v2 * c - center).squaredNorm() <= r2) ++inside;
      }
    }
  }
  return area * inside / (n * n);
}

}  // namespace

SkullSurface::SkullSurface(const TriMesh& skull) {
  skull.validate("skull mesh");
  if (skull.triangles.empty()) throw InputError("skull mesh", "", "has no triangles");
  m_impl = std::make_unique<Impl>(skull);
  Impl& s = *m_impl;
  s.face_normal = face_normals(skull);
  s.face_area.resize(skull.triangles.size());
  for (std::size_t t = 0; t < skull.triangles.size(); ++t) {
    const Tri& f = skull.triangles[t];
    s.face_area[t] = triangle_area(skull.positions[f[0]], skull.positions[f[1]], skull.positions[f[2]]);
  }
  // Edge adjacency: sort (edge, triangle) records and link triangles sharing an edge.
  std::vector<std::pair<std::uint64_t, Index>> edges;
  edges.reserve(skull.triangles.size() * 3);
  for (std::size_t t = 0; t < skull.triangles.size(); ++t) {
    const Tri& f = skull.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(std::min(f[k], f[(k + 1) % 3]));
      const auto b = static_cast<std::uint32_t>(std::max(f[k], f[(k + 1) % 3]));
      edges.emplace_back((std::uint64_t(a) << 32) | b, static_cast<Index>(t));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::vector<Index>> neighbours(skull.triangles.size());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    for (std::size_t p = i; p < j; ++p) {
      for (std::size_t q = i; q < j; ++q) {
        if (p != q) neighbours[edges[p].second].push_back(edges[q].second);
      }
    }
    i = j;
  }
  s.adjacency_offsets.assign(skull.triangles.size() + 1, 0);
  for (std::size_t t = 0; t < neighbours.size(); ++t) {
    std::sort(neighbours[t].begin(), neighbours[t].end());
    neighbours[t].erase(std::unique(neighbours[t].begin(), neighbours[t].end()), neighbours[t].end());
    s.adjacency_offsets[t + 1] = s.adjacency_offsets[t] + static_cast<Index>(neighbours[t].size());
  }
  s.adjacency.reserve(static_cast<std::size_t>(s.adjacency_offsets.back()));
  for (const auto& n : neighbours) s.adjacency.insert(s.adjacency.end(), n.begin(), n.end());
}

SkullSurface::~SkullSurface() = default;
SkullSurface::SkullSurface(SkullSurface&&) noexcept = default;
SkullSurface& SkullSurface::operator=(SkullSurface&&) noexcept = default;

const TriMesh& SkullSurface::mesh() const {
  return m_impl->mesh;
}

ClosestPoint SkullSurface::closest_point(const Vec3& point) const {
  const auto hit = m_impl->query.query(point);
  if (!hit) throw InputError("skull mesh", "", "no closest point (empty mesh)");
  return *hit;
}

Vec3 SkullSurface::patch_normal(const ClosestPoint& at, double radius_mm) const {
  const Impl& s = *m_impl;
  if (!(radius_mm >= 0.0) || !std::isfinite(radius_mm)) {
    throw InputError("skull normal", "patch radius", "must be a finite length >= 0 mm");
  }
  if (at.triangle < 0 || static_cast<std::size_t>(at.triangle) >= s.mesh.triangles.size()) {
    throw InputError("skull normal", "closest point", "triangle index out of range");
  }
  const Vec3 seed_normal = s.face_normal[at.triangle];
  Vec3 sum = Vec3::Zero();
  std::vector<Index> stack = {at.triangle};
  std::unordered_set<Index> visited = {at.triangle};
  const double r2 = radius_mm * radius_mm;
  while (!stack.empty()) {
    const Index t = stack.back();
    stack.pop_back();
    const Tri& f = s.mesh.triangles[t];
    const Vec3& a = s.mesh.positions[f[0]];
    const Vec3& b = s.mesh.positions[f[1]];
    const Vec3& c = s.mesh.positions[f[2]];
    sum += area_inside_ball(a, b, c, at.point, radius_mm, s.face_area[t]) * s.face_normal[t];
    for (Index k = s.adjacency_offsets[t]; k < s.adjacency_offsets[t + 1]; ++k) {
      const Index n = s.adjacency[k];
      if (!visited.insert(n).second) continue;
      if (s.face_normal[n].dot(seed_normal) <= 0.0) continue;  // far side of thin bone, or a fold
      const Tri& g = s.mesh.triangles[n];
      const Vec3 w =
          closest_point_on_triangle(at.point, s.mesh.positions[g[0]], s.mesh.positions[g[1]], s.mesh.positions[g[2]]);
      const Vec3 q = w[0] * s.mesh.positions[g[0]] + w[1] * s.mesh.positions[g[1]] + w[2] * s.mesh.positions[g[2]];
      if ((q - at.point).squaredNorm() <= r2) stack.push_back(n);
    }
  }
  const double norm = sum.norm();
  if (norm <= 1e-300) return seed_normal;
  return sum / norm;
}

Vec3 SkullSurface::landmark_direction(const Vec3& landmark_mm, double radius_mm) const {
  return patch_normal(closest_point(landmark_mm), radius_mm);
}

DepthVectors depth_vectors(const SkullSurface& skull, const LandmarkSet& skull_landmarks, const TissueDepths& depths,
                           const DepthVectorOptions& options) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::string source = skull_landmarks.name().empty() ? std::string("skull landmarks")
                                                            : "skull landmarks '" + skull_landmarks.name() + "'";
  DepthVectors out;
  for (const Landmark& l : skull_landmarks.landmarks()) {
    const LandmarkRef ref = vocabulary.resolve(l.name, source, l.name);
    const LandmarkSite& site = vocabulary.site(ref);
    const auto skin = vocabulary.paired(ref);
    if (site.surface != LandmarkSurface::bone || !skin) {
      out.unpaired.push_back(vocabulary.name(ref));
      continue;
    }
    const TissueDepthEntry* entry = depths.find_site(site.abbreviation);
    if (entry == nullptr) {
      out.missing.push_back(vocabulary.name(ref));
      continue;
    }
    const ClosestPoint at = skull.closest_point(l.position_mm);
    if (at.distance > options.max_surface_offset_mm) {
      throw InputError(source, vocabulary.name(ref),
                       fmt::format("landmark lies {:.1f} mm from the skull surface (more than {} mm: wrong skull, "
                                   "units or coordinate system?)",
                                   at.distance, options.max_surface_offset_mm));
    }
    DepthVector v;
    v.bone_landmark = vocabulary.name(ref);
    v.skin_landmark = vocabulary.name(*skin);
    v.bone_mm = at.point;
    v.direction = skull.patch_normal(at, options.patch_radius_mm);
    v.depth_mm = entry->mean_mm;
    v.skin_mm = v.bone_mm + v.depth_mm * v.direction;
    v.surface_offset_mm = at.distance;
    v.source = l.source;
    v.confidence = l.confidence;
    v.depth_source = depths.table + " (" + depths.group.describe() + ", " + depths.variant + "): " + entry->source;
    out.vectors.push_back(std::move(v));
  }
  return out;
}

LandmarkSet skin_landmarks(const DepthVectors& vectors, const std::string& name) {
  LandmarkSet set(name);
  for (const DepthVector& v : vectors.vectors) set.add({v.skin_landmark, v.skin_mm, v.source, v.confidence});
  return set;
}

}  // namespace forensim
