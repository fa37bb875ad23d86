#include "spatial/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "spatial/embree_scene.hpp"

namespace forensim {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return Vec3(1, 0, 0);  // vertex region a

  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return Vec3(0, 1, 0);  // vertex region b

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge region ab
    const double denom = d1 - d3;
    const double v = denom > 0.0 ? d1 / denom : 0.0;
    return Vec3(1.0 - v, v, 0.0);
  }

  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return Vec3(0, 0, 1);  // vertex region c

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge region ac
    const double denom = d2 - d6;
    const double w = denom > 0.0 ? d2 / denom : 0.0;
    return Vec3(1.0 - w, 0.0, w);
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge region bc
    const double denom = (d4 - d3) + (d5 - d6);
    const double w = denom > 0.0 ? (d4 - d3) / denom : 0.0;
    return Vec3(0.0, 1.0 - w, w);
  }

  const double sum = va + vb + vc;
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    // Degenerate (collinear) triangle that slipped through the region tests: best of its three edges.
    Vec3 best(1, 0, 0);
    double best_d2 = (p - a).squaredNorm();
    const Vec3* v[3] = {&a, &b, &c};
    for (int e = 0; e < 3; ++e) {
      const Vec3& s = *v[e];
      const Vec3& q = *v[(e + 1) % 3];
      const Vec3 d = q - s;
      const double len2 = d.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - s).dot(d) / len2, 0.0, 1.0) : 0.0;
      const double dist2 = (s + t * d - p).squaredNorm();
      if (dist2 < best_d2) {
        best_d2 = dist2;
        best = Vec3::Zero();
        best[e] = 1.0 - t;
        best[(e + 1) % 3] = t;
      }
    }
    return best;
  }
  const double denom = 1.0 / sum;
  const double v = vb * denom;
  const double w = vc * denom;
  return Vec3(1.0 - v - w, v, w);
}

std::optional<ClosestPoint> closest_point(const TriMesh& mesh, const Vec3& point, double max_distance) {
  // Plain tests first: this runs once per query point, and require_input's string arguments would be built
  // on every call.
  if (!point.allFinite()) throw InputError("closest point query", "point", "query point is not finite");
  if (!(max_distance >= 0.0)) throw InputError("closest point query", "max_distance", "max_distance must be >= 0");
  std::optional<ClosestPoint> best;
  double best_d2 = std::isinf(max_distance) ? max_distance : max_distance * max_distance;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& tri = mesh.triangles[f];
    const Vec3& a = mesh.positions[tri[0]];
    const Vec3& b = mesh.positions[tri[1]];
    const Vec3& c = mesh.positions[tri[2]];
    const Vec3 bary = closest_point_on_triangle(point, a, b, c);
    const Vec3 q = bary[0] * a + bary[1] * b + bary[2] * c;
    const double d2 = (q - point).squaredNorm();
    if (d2 > best_d2 || (best && d2 == best_d2)) continue;
    best = ClosestPoint{static_cast<Index>(f), bary, q, std::sqrt(d2)};
    best_d2 = d2;
  }
  return best;
}

namespace {

struct QueryState {
  const Vec3* corners;  ///< 3 per triangle, in triangle order (double, world coordinates)
  Vec3 point;           ///< world coordinates, double
  double margin;        ///< added to the search radius to cover float rounding of bounds and query point
  double best_d2;       ///< squared distance of the best triangle so far
  double max_d2;        ///< squared max_distance
  Index best_triangle;
  Vec3 best_barycentric;
};

bool closest_point_callback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<QueryState*>(args->userPtr);
  const unsigned prim = args->primID;
  const Vec3* corner = state->corners + 3 * static_cast<std::size_t>(prim);
  const Vec3& a = corner[0];
  const Vec3& b = corner[1];
  const Vec3& c = corner[2];
  // The distance to the triangle's bounding box is a lower bound of the distance to the triangle: a triangle
  // whose box lies farther than the best so far (or the limit) cannot win, and skips the exact test. The slack
  // covers rounding, so no triangle the exact test would keep is skipped.
  const Vec3& p = state->point;
  const Vec3 below = a.cwiseMin(b).cwiseMin(c) - p;
  const Vec3 above = p - a.cwiseMax(b).cwiseMax(c);
  const double box_d2 = below.cwiseMax(above).cwiseMax(0.0).squaredNorm();
  const double bound = std::min(state->best_d2, state->max_d2);
  if (box_d2 > bound * (1.0 + 1e-12) + 1e-300) return false;
  const Vec3 bary = closest_point_on_triangle(p, a, b, c);
  const Vec3 q = bary[0] * a + bary[1] * b + bary[2] * c;
  const double d2 = (q - p).squaredNorm();
  if (d2 > state->max_d2) return false;
  const Index index = static_cast<Index>(prim);
  if (d2 < state->best_d2 || (d2 == state->best_d2 && index < state->best_triangle)) {
    state->best_d2 = d2;
    state->best_triangle = index;
    state->best_barycentric = bary;
    const float radius = static_cast<float>(std::sqrt(d2) + state->margin);
    if (radius < args->query->radius) {
      args->query->radius = radius;
      return true;
    }
  }
  return false;
}

}  // namespace

struct ClosestPointQuery::Impl {
  explicit Impl(const TriMesh& mesh) : scene(mesh, "closest point mesh", false) {
    corners.reserve(3 * scene.triangles().size());
    for (const Tri& t : scene.triangles()) {
      for (int k = 0; k < 3; ++k) corners.push_back(scene.positions()[static_cast<std::size_t>(t[k])]);
    }
  }

  std::optional<ClosestPoint> query(const Vec3& point, double max_distance) const {
    if (scene.empty()) return std::nullopt;
    QueryState state;
    state.corners = corners.data();
    state.point = point;
    const Vec3 local = point - scene.shift();
    // Float rounding of the stored vertices (relative to the centre) and of the query point.
    state.margin = 1e-6 * (scene.extent() + local.norm()) + 1e-30;
    state.best_d2 = std::numeric_limits<double>::infinity();
    state.max_d2 = std::isinf(max_distance) ? max_distance : max_distance * max_distance;
    state.best_triangle = std::numeric_limits<Index>::max();
    state.best_barycentric = Vec3::Zero();

    RTCPointQuery query;
    query.x = static_cast<float>(local.x());
    query.y = static_cast<float>(local.y());
    query.z = static_cast<float>(local.z());
    query.time = 0.0f;
    query.radius = std::isinf(max_distance) ? std::numeric_limits<float>::infinity()
                                            : static_cast<float>(max_distance + state.margin);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene.scene(), &query, &context, closest_point_callback, &state);
    if (state.best_triangle == std::numeric_limits<Index>::max()) return std::nullopt;

    ClosestPoint result;
    result.triangle = state.best_triangle;
    result.barycentric = state.best_barycentric;
    const Tri& tri = scene.triangles()[result.triangle];
    result.point = state.best_barycentric[0] * scene.positions()[tri[0]] +
                   state.best_barycentric[1] * scene.positions()[tri[1]] +
                   state.best_barycentric[2] * scene.positions()[tri[2]];
    result.distance = std::sqrt(state.best_d2);
    return result;
  }

  EmbreeScene scene;
  std::vector<Vec3> corners;
};

ClosestPointQuery::ClosestPointQuery(const TriMesh& mesh) : m_impl(std::make_unique<Impl>(mesh)) {}
ClosestPointQuery::~ClosestPointQuery() = default;
ClosestPointQuery::ClosestPointQuery(ClosestPointQuery&&) noexcept = default;
ClosestPointQuery& ClosestPointQuery::operator=(ClosestPointQuery&&) noexcept = default;

std::size_t ClosestPointQuery::triangle_count() const {
  return m_impl->scene.triangles().size();
}

std::optional<ClosestPoint> ClosestPointQuery::query(const Vec3& point, double max_distance) const {
  // Plain tests first: this runs once per query point, and require_input's string arguments would be built
  // on every call.
  if (!point.allFinite()) throw InputError("closest point query", "point", "query point is not finite");
  if (!(max_distance >= 0.0)) throw InputError("closest point query", "max_distance", "max_distance must be >= 0");
  return m_impl->query(point, max_distance);
}

std::vector<std::optional<ClosestPoint>> ClosestPointQuery::query_batch(const std::vector<Vec3>& points,
                                                                        double max_distance) const {
  require_input(max_distance >= 0.0, "closest point query", "max_distance", "max_distance must be >= 0");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw InputError("closest point query", "point " + std::to_string(i), "query point is not finite");
  }
  std::vector<std::optional<ClosestPoint>> results(points.size());
  parallel_for(
      0, points.size(), [&](std::size_t i) { results[i] = m_impl->query(points[i], max_distance); }, 64);
  return results;
}

}  // namespace forensim

namespace forensim {

std::vector<std::optional<ClosestPoint>> ClosestPointQuery::query_batch_bounded(
    const std::vector<Vec3>& points, const std::vector<double>& upper_bounds) const {
  require_input(
      upper_bounds.size() == points.size(), "closest point query", "upper_bounds",
      "has " + std::to_string(upper_bounds.size()) + " entries for " + std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw InputError("closest point query", "point " + std::to_string(i), "query point is not finite");
    if (!(upper_bounds[i] >= 0.0))
      throw InputError("closest point query", "upper bound " + std::to_string(i), "must be >= 0");
  }
  const double slack = 1e-9 * m_impl->scene.extent() + 1e-12;
  std::vector<std::optional<ClosestPoint>> results(points.size());
  parallel_for(
      0, points.size(),
      [&](std::size_t i) {
        const double bound = upper_bounds[i];
        // Widened a little: the bound is itself computed in double (a point "on" the mesh is on it to rounding).
        if (std::isfinite(bound)) results[i] = m_impl->query(points[i], bound * (1.0 + 1e-9) + slack);
        if (!results[i]) results[i] = m_impl->query(points[i], std::numeric_limits<double>::infinity());
      },
      64);
  return results;
}

}  // namespace forensim
