#include "body/tracking.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/tet_boundary.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "spatial/winding_number.hpp"

namespace forensim {
namespace {

double mean_edge_length(const TriMesh& mesh) {
  if (mesh.triangles.empty()) return 0.0;
  const double sum = parallel_sum(0, mesh.triangles.size(), [&](std::size_t f) {
    const Tri& t = mesh.triangles[f];
    const Vec3& a = mesh.positions[t[0]];
    const Vec3& b = mesh.positions[t[1]];
    const Vec3& c = mesh.positions[t[2]];
    return (b - a).norm() + (c - b).norm() + (a - c).norm();
  });
  return sum / (3.0 * static_cast<double>(mesh.triangles.size()));
}

/// The boundary faces as a triangle mesh over the nodes they use (same triangle order and corner order, so
/// a triangle's barycentrics weight its face's nodes). Throws InputError for a node out of range.
TriMesh boundary_mesh(const std::vector<TetFace>& faces, const std::vector<Vec3>& nodes) {
  TriMesh out;
  out.triangles.reserve(faces.size());
  std::vector<Index> vertex_of_node(nodes.size(), -1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    Tri t = faces[f].vertices;
    for (Index& v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= nodes.size())
        throw InputError(
            "tracking boundary faces", "face " + std::to_string(f),
            "node " + std::to_string(v) + " is outside the " + std::to_string(nodes.size()) + " volume nodes");
      if (vertex_of_node[v] < 0) {
        vertex_of_node[v] = static_cast<Index>(out.positions.size());
        out.positions.push_back(nodes[v]);
      }
      v = vertex_of_node[v];
    }
    out.triangles.push_back(t);
  }
  return out;
}

/// A boundary point found for one skin vertex, before the tet-node mapping.
struct Found {
  Index triangle = -1;
  Vec3 barycentric = Vec3::Zero();
  TrackingSide side = TrackingSide::outside;
  TrackingMethod method = TrackingMethod::closest_point;
};

/// The nearest valid ray hit for a skin vertex at `p` with unit normal `n`, or nullopt. The first hit of
/// the -n ray tells the side for a closed boundary: a front face (entered from outside) or a back face
/// (left from inside). From inside, the +n ray's first hit also leaves the volume; from outside, a +n ray
/// would enter through a face turned away from the skin, the wrong side, so it is not cast.
std::optional<Found> ray_attach(const RayCaster& rays, const Vec3& p, const Vec3& n, double max_distance,
                                bool try_positive) {
  std::optional<Found> best;
  double best_t = std::numeric_limits<double>::infinity();
  const std::optional<RayHit> down = rays.intersect(p, -n, 0.0, max_distance);
  bool inside_known = false;
  if (down) {
    const bool entering = (-n).dot(down->normal) < 0.0;
    best = Found{down->triangle, down->barycentric, entering ? TrackingSide::outside : TrackingSide::inside,
                 TrackingMethod::ray_negative_normal};
    best_t = down->t;
    inside_known = !entering;
    if (entering) return best;  // outside: +n could only enter the volume on the wrong side
  }
  if (!try_positive) return best;
  // Inside (known from the -n hit) or unknown (no -n hit within reach): a +n hit counts only when it
  // leaves the volume, which also proves the vertex is inside.
  const std::optional<RayHit> up =
      rays.intersect(p, n, 0.0, std::min(max_distance, best_t), inside_known ? FaceCulling::front : FaceCulling::none);
  if (up && n.dot(up->normal) > 0.0 && up->t < best_t)
    best = Found{up->triangle, up->barycentric, TrackingSide::inside, TrackingMethod::ray_positive_normal};
  return best;
}

}  // namespace

double TrackingStats::ray_fraction() const {
  if (count == 0) return 0.0;
  const std::size_t rays = method_counts[static_cast<int>(TrackingMethod::ray_negative_normal)] +
                           method_counts[static_cast<int>(TrackingMethod::ray_positive_normal)];
  return static_cast<double>(rays) / static_cast<double>(count);
}

TrackingConnections compute_tracking(const TriMesh& skin, const TetMesh& volume, const TrackingOptions& options) {
  volume.validate("tracking volume mesh");
  return compute_tracking(skin, volume, tet_boundary_faces(volume), options);
}

TrackingConnections compute_tracking(const TriMesh& skin, const TetMesh& volume, const std::vector<TetFace>& faces,
                                     const TrackingOptions& options) {
  skin.validate("tracking skin mesh");
  if (volume.tets.empty() || faces.empty())
    throw InputError("tracking volume mesh", "", "the volume has no tets (or no boundary faces)");
  if (!(options.max_distance_mm >= 0.0) || !std::isfinite(options.max_distance_mm) ||
      !(options.max_distance_edge_factor >= 0.0) || !std::isfinite(options.max_distance_edge_factor))
    throw InputError("tracking options", "max distance", "must be finite and non-negative");

  const TriMesh boundary = boundary_mesh(faces, volume.positions);
  const std::vector<Vec3> normals = skin.normals.size() == skin.positions.size() ? skin.normals : vertex_normals(skin);
  const double max_distance =
      std::max(options.max_distance_mm, options.max_distance_edge_factor * mean_edge_length(skin));

  const RayCaster rays(boundary);
  const std::size_t count = skin.positions.size();
  std::vector<std::optional<Found>> found(count);
  parallel_for(
      0, count,
      [&](std::size_t i) {
        const Vec3& n = normals[i];
        const double length = n.norm();
        if (!(length > 0.0) || !std::isfinite(length)) return;
        found[i] = ray_attach(rays, skin.positions[i], n / length, max_distance, options.try_positive_normal);
      },
      64);

  // Fallback for the rest: closest boundary point, side by the winding number of the closed boundary.
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < count; ++i)
    if (!found[i]) missing.push_back(i);
  if (!missing.empty()) {
    const ClosestPointQuery closest(boundary);
    const WindingNumber winding(boundary);
    parallel_for(
        0, missing.size(),
        [&](std::size_t k) {
          const std::size_t i = missing[k];
          const Vec3& p = skin.positions[i];
          const std::optional<ClosestPoint> cp = closest.query(p);
          if (!cp) throw InputError("tracking volume mesh", "", "the volume boundary has no triangles");
          found[i] =
              Found{cp->triangle, cp->barycentric, winding.inside(p) ? TrackingSide::inside : TrackingSide::outside,
                    TrackingMethod::closest_point};
        },
        16);
  }

  // Sized at construction: resize() on a default-constructed vector trips GCC 12's -Wnull-dereference.
  TrackingConnections out{std::vector<Index>(count, -1),
                          std::vector<Tri>(count),
                          std::vector<Vec3>(count, Vec3::Zero()),
                          std::vector<double>(count, 0.0),
                          std::vector<TrackingSide>(count, TrackingSide::outside),
                          std::vector<TrackingMethod>(count, TrackingMethod::closest_point)};
  parallel_for(0, count, [&](std::size_t i) {
    const Found& f = *found[i];
    // The boundary mesh's triangle f.triangle is faces[f.triangle] with compacted vertices, in the same
    // corner order, so its barycentrics are the weights of the face's tet nodes.
    Vec3 w = f.barycentric.cwiseMax(0.0);
    const double sum = w.sum();
    w = sum > 0.0 ? Vec3(w / sum) : Vec3(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
    const Tri& nodes = faces[f.triangle].vertices;
    const Vec3 t =
        w[0] * volume.positions[nodes[0]] + w[1] * volume.positions[nodes[1]] + w[2] * volume.positions[nodes[2]];
    out.boundary_face[i] = f.triangle;
    out.face_nodes[i] = nodes;
    out.weights[i] = w;
    out.rest_distance[i] = (t - skin.positions[i]).norm();
    out.side[i] = f.side;
    out.method[i] = f.method;
  });
  return out;
}

std::vector<Vec3> tracking_points(const TrackingConnections& tracking, const std::vector<Vec3>& node_positions) {
  const std::size_t count = tracking.size();
  if (tracking.face_nodes.size() != count || tracking.weights.size() != count)
    throw InputError("tracking connections", "", "face_nodes and weights must have one entry per connection");
  const std::size_t node_count = node_positions.size();
  for (std::size_t i = 0; i < count; ++i)
    for (const Index v : tracking.face_nodes[i])
      if (v < 0 || static_cast<std::size_t>(v) >= node_count)
        throw InputError(
            "tracking connections", "tracking connection " + std::to_string(i),
            "face node " + std::to_string(v) + " is outside the " + std::to_string(node_count) + " node positions");
  std::vector<Vec3> points(count);
  parallel_for(0, count, [&](std::size_t i) {
    const Tri& k = tracking.face_nodes[i];
    const Vec3& w = tracking.weights[i];
    points[i] = w[0] * node_positions[k[0]] + w[1] * node_positions[k[1]] + w[2] * node_positions[k[2]];
  });
  return points;
}

TrackingStats tracking_stats(const TrackingConnections& tracking) {
  TrackingStats s;
  s.count = tracking.size();
  if (s.count == 0) return s;
  s.min_distance = std::numeric_limits<double>::infinity();
  s.max_distance = 0.0;
  for (std::size_t i = 0; i < s.count; ++i) {
    ++s.method_counts[std::clamp(static_cast<int>(tracking.method[i]), 0, tracking_method_count - 1)];
    if (tracking.side[i] == TrackingSide::inside) ++s.inside_count;
    s.min_distance = std::min(s.min_distance, tracking.rest_distance[i]);
    s.max_distance = std::max(s.max_distance, tracking.rest_distance[i]);
  }
  s.mean_distance =
      parallel_sum(0, s.count, [&](std::size_t i) { return tracking.rest_distance[i]; }) / static_cast<double>(s.count);
  return s;
}

void validate_tracking(const TrackingConnections& tracking, std::size_t skin_vertex_count, std::size_t node_count,
                       std::size_t boundary_face_count, const std::string& source) {
  const std::size_t n = skin_vertex_count;
  auto check_size = [&](std::size_t size, const char* name) {
    if (size != n)
      throw InputError(source, std::string("tracking ") + name,
                       "has " + std::to_string(size) + " entries for " + std::to_string(n) + " skin vertices");
  };
  check_size(tracking.boundary_face.size(), "boundary_face");
  check_size(tracking.face_nodes.size(), "face_nodes");
  check_size(tracking.weights.size(), "weights");
  check_size(tracking.rest_distance.size(), "rest_distance");
  check_size(tracking.side.size(), "side");
  check_size(tracking.method.size(), "method");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string where = "tracking connection " + std::to_string(i);
    const Index f = tracking.boundary_face[i];
    if (f < 0 || static_cast<std::size_t>(f) >= boundary_face_count)
      throw InputError(source, where,
                       "boundary face " + std::to_string(f) + " is outside the " + std::to_string(boundary_face_count) +
                           " boundary faces");
    for (const Index v : tracking.face_nodes[i])
      if (v < 0 || static_cast<std::size_t>(v) >= node_count)
        throw InputError(
            source, where,
            "face node " + std::to_string(v) + " is outside the " + std::to_string(node_count) + " volume nodes");
    const Vec3& w = tracking.weights[i];
    if (!w.allFinite() || w.minCoeff() < -1e-9 || std::abs(w.sum() - 1.0) > 1e-9)
      throw InputError(source, where, "barycentric weights must be finite, non-negative and sum to 1");
    const double d = tracking.rest_distance[i];
    if (!std::isfinite(d) || d < 0.0) throw InputError(source, where, "rest distance must be finite and >= 0");
    if (tracking.side[i] != TrackingSide::inside && tracking.side[i] != TrackingSide::outside)
      throw InputError(source, where, "unknown side");
    if (static_cast<int>(tracking.method[i]) >= tracking_method_count)
      throw InputError(source, where, "unknown method");
  }
}

const char* tracking_method_name(TrackingMethod method) {
  switch (method) {
    case TrackingMethod::ray_negative_normal:
      return "ray -n";
    case TrackingMethod::ray_positive_normal:
      return "ray +n";
    case TrackingMethod::closest_point:
      return "closest point";
  }
  return "unknown";
}

}  // namespace forensim
