#pragma once
/// Nearest point of a point cloud: the reverse pairs of the non-rigid skull registration (each target sample's
/// nearest moving reference sample) and other point-to-cloud searches. A CGAL k-d tree (Orthogonal_k_neighbor_search
/// over the points' indices), built once per cloud; queries are exact in double.

#include <memory>
#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Nearest neighbour of a point among a fixed set of points.
struct NearestPoint {
  std::size_t index = 0;  ///< index into the cloud's points
  double distance = 0.0;  ///< Euclidean distance to the query (mm for points in mm)
};

/// Setup-once, query-many nearest-point search over a copy of `points`. Queries are const and thread-safe (the
/// tree is built in the constructor); the answer to a query does not depend on other queries or on the thread
/// count. Among equally near points the one the tree meets first is returned (the same for the same cloud).
class NearestPointIndex {
 public:
  /// Copies and indexes `points`. Throws InputError naming "point cloud" when a point is not finite. An empty
  /// cloud is allowed (queries return nothing).
  explicit NearestPointIndex(const std::vector<Vec3>& points);
  ~NearestPointIndex();
  NearestPointIndex(NearestPointIndex&&) noexcept;
  NearestPointIndex& operator=(NearestPointIndex&&) noexcept;

  std::size_t size() const;
  /// The nearest cloud point of `query` (finite, else InputError). Throws InputError when the cloud is empty.
  NearestPoint nearest(const Vec3& query) const;
  /// nearest() for every query, in parallel; result i belongs to queries[i] whatever the thread count.
  std::vector<NearestPoint> nearest_batch(const std::vector<Vec3>& queries) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Nearest point by testing every point, O(#points): the reference the index is tested against.
NearestPoint nearest_point_brute_force(const std::vector<Vec3>& points, const Vec3& query);

}  // namespace forensim
