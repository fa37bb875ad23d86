// A false positive of -Wnull-dereference inside CGAL's Kd_tree::build (a std::vector resize) after inlining:
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include "spatial/nearest_point.hpp"

#include <CGAL/Euclidean_distance.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point3 = Kernel::Point_3;

/// The tree stores indices; this map gives each index its point.
struct IndexToPoint {
  using key_type = std::size_t;
  using value_type = Point3;
  using reference = const Point3&;
  using category = boost::readable_property_map_tag;
  const std::vector<Point3>* points = nullptr;
  friend reference get(const IndexToPoint& map, std::size_t i) { return (*map.points)[i]; }
};

using BaseTraits = CGAL::Search_traits_3<Kernel>;
using Traits = CGAL::Search_traits_adapter<std::size_t, IndexToPoint, BaseTraits>;
using Distance = CGAL::Distance_adapter<std::size_t, IndexToPoint, CGAL::Euclidean_distance<BaseTraits>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits, Distance>;
using Tree = Search::Tree;

void check_finite(const Vec3& p, const char* what, std::size_t i) {
  if (!p.allFinite()) throw InputError(what, "point " + std::to_string(i), "is not finite");
}

}  // namespace

struct NearestPointIndex::Impl {
  std::vector<Point3> points;
  IndexToPoint map;
  std::unique_ptr<Tree> tree;

  /// The nearest point of a finite query in a non-empty cloud.
  NearestPoint nearest(const Vec3& query) const {
    const Search search(*tree, Point3(query.x(), query.y(), query.z()), 1, 0.0, true, Distance(map));
    const auto best = search.begin();
    return {best->first, std::sqrt(best->second)};
  }
};

NearestPointIndex::NearestPointIndex(const std::vector<Vec3>& points) : impl_(std::make_unique<Impl>()) {
  impl_->points.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_finite(points[i], "point cloud", i);
    impl_->points.emplace_back(points[i].x(), points[i].y(), points[i].z());
  }
  impl_->map.points = &impl_->points;
  std::vector<std::size_t> indices;
  indices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) indices.push_back(i);
  impl_->tree = std::make_unique<Tree>(indices.begin(), indices.end(), Tree::Splitter(), Traits(impl_->map));
  // Built here, not on the first query: the lazy build is not thread-safe.
  if (!points.empty()) impl_->tree->build();
}

NearestPointIndex::~NearestPointIndex() = default;
NearestPointIndex::NearestPointIndex(NearestPointIndex&&) noexcept = default;
NearestPointIndex& NearestPointIndex::operator=(NearestPointIndex&&) noexcept = default;

std::size_t NearestPointIndex::size() const {
  return impl_->points.size();
}

NearestPoint NearestPointIndex::nearest(const Vec3& query) const {
  check_finite(query, "nearest point query", 0);
  require_input(!impl_->points.empty(), "nearest point query", "", "the point cloud is empty");
  return impl_->nearest(query);
}

std::vector<NearestPoint> NearestPointIndex::nearest_batch(const std::vector<Vec3>& queries) const {
  for (std::size_t i = 0; i < queries.size(); ++i) check_finite(queries[i], "nearest point query", i);
  require_input(queries.empty() || !impl_->points.empty(), "nearest point query", "", "the point cloud is empty");
  std::vector<NearestPoint> out(queries.size());
  parallel_for(
      0, queries.size(), [&](std::size_t i) { out[i] = impl_->nearest(queries[i]); }, 64);
  return out;
}

NearestPoint nearest_point_brute_force(const std::vector<Vec3>& points, const Vec3& query) {
  require_input(!points.empty(), "nearest point query", "", "the point cloud is empty");
  NearestPoint best{0, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = (points[i] - query).norm();
    if (d < best.distance) best = {i, d};
  }
  return best;
}

}  // namespace forensim
