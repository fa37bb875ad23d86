#pragma once
/// Closest point on a triangle mesh: where the desiccation skin attaches when no ray along the negative
/// vertex normal reaches the tet boundary, and distances from points to skins and skulls.

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Closest point found on a mesh.
struct ClosestPoint {
  Index triangle = -1;              ///< index into mesh.triangles (lowest index among equally close ones)
  Vec3 barycentric = Vec3::Zero();  ///< weights of the triangle's vertices 0, 1, 2 (each >= 0, sum 1)
  Vec3 point = Vec3::Zero();        ///< the closest point, = sum of barycentric weights times vertices
  double distance = 0.0;            ///< Euclidean distance from the query point (mm for meshes in mm)
};

/// Barycentric coordinates (weights of a, b, c) of the point of triangle (a, b, c) closest to p, in
/// double, by Voronoi regions (Ericson, Real-Time Collision Detection, 2005, section 5.1.5). Degenerate
/// triangles are handled (the result is a closest point of the segment or vertex they collapse to).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Closest point of `mesh` to `point` by testing every triangle in double, O(#F): for one-off queries
/// (build a ClosestPointQuery for more) and as a reference. Same conventions as ClosestPointQuery::query().
std::optional<ClosestPoint> closest_point(const TriMesh& mesh, const Vec3& point,
                                          double max_distance = std::numeric_limits<double>::infinity());

/// Setup-once, query-many closest-point search. Uses Embree 3's BVH through rtcPointQuery: Embree culls
/// triangles whose float bounds lie outside the current search sphere, and a callback measures the exact
/// double distance with closest_point_on_triangle() and shrinks the sphere (with a margin for float
/// rounding, so no closer triangle is culled). Reusing Embree's BVH saves writing and tuning our own; its
/// float bounds only prune, they never decide the answer. Queries are const and thread-safe.
class ClosestPointQuery {
 public:
  /// Validates `mesh` (InputError naming "closest point mesh") and builds the BVH. Copies positions and
  /// triangles; an empty mesh is allowed (every query returns nullopt).
  explicit ClosestPointQuery(const TriMesh& mesh);
  ~ClosestPointQuery();
  ClosestPointQuery(ClosestPointQuery&&) noexcept;
  ClosestPointQuery& operator=(ClosestPointQuery&&) noexcept;

  /// Closest point of the mesh to `point`, or nullopt when the mesh is empty or nothing lies within
  /// `max_distance` (inclusive). `point` must be finite (else InputError).
  std::optional<ClosestPoint> query(const Vec3& point,
                                    double max_distance = std::numeric_limits<double>::infinity()) const;

  /// query() for every point, in parallel; result i belongs to points[i] whatever the thread count.
  std::vector<std::optional<ClosestPoint>> query_batch(
      const std::vector<Vec3>& points, double max_distance = std::numeric_limits<double>::infinity()) const;

  /// query_batch() with an upper bound on each point's distance to the mesh (#points bounds, mm; for example the
  /// distance to a point known to lie on the mesh, such as the previous closest point of a point that moved a
  /// little): each search starts from that radius instead of an unbounded one, so the BVH prunes more from the
  /// start. The results equal query_batch(points) exactly: a point with nothing within its bound (the bound was
  /// wrong) is searched again without one. Throws InputError for a size mismatch, a non-finite point or a
  /// negative or NaN bound (infinity is allowed: no bound).
  std::vector<std::optional<ClosestPoint>> query_batch_bounded(const std::vector<Vec3>& points,
                                                               const std::vector<double>& upper_bounds) const;

  std::size_t triangle_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace forensim
