#pragma once
/// Tracking connections between the desiccation skin and the tet volume (Frerichs, Vidler and Gatzidis 2020,
/// "Computer graphics simulation of natural mummification by desiccation", section 8.2, Figures 1 and 2): every skin
/// vertex p_i is tied to a tracking point t_i on the volume's boundary faces, stored as a boundary face and barycentric
/// weights of its three tet-mesh NODES, so t_i follows the volume as it deforms, plus the initial distance |t_i - p_i|
/// from which the tracking constraint's radius grows (eqs. 32-35). The tracking point is where the ray along the
/// vertex's negative normal meets the boundary; when no ray meets it from the correct side within a maximum distance,
/// the closest boundary point.

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tet_boundary.hpp"
#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// How a tracking point was found.
enum class TrackingMethod : std::uint8_t {
  ray_negative_normal = 0,  ///< ray along -n_i: enters the volume from outside, or leaves it from inside
  ray_positive_normal = 1,  ///< ray along +n_i from a skin vertex inside the volume, leaving it
  closest_point = 2,        ///< fallback: no ray hit within the maximum distance from the correct side
};

/// Number of TrackingMethod values.
inline constexpr int tracking_method_count = 3;

/// Which side of the volume boundary a skin vertex lies on.
enum class TrackingSide : std::int8_t {
  inside = -1,  ///< the skin vertex lies inside the volume (the skin dips under the boundary)
  outside = 1,  ///< the skin vertex lies outside (or on) the volume boundary: the usual case
};

struct TrackingOptions {
  /// Rays count up to max(max_distance_mm, max_distance_edge_factor * mean skin edge length) (mm); the
  /// closest-point fallback has no limit.
  double max_distance_mm = 5.0;
  double max_distance_edge_factor = 3.0;
  /// For skin vertices inside the volume, also cast a ray along +n_i (and keep the nearer valid hit).
  bool try_positive_normal = true;
};

/// One tracking connection per skin vertex, as flat per-vertex arrays (Model data: fixed during a run).
/// Boundary faces are numbered as in tet_boundary_faces(volume) (no label).
struct TrackingConnections {
  std::vector<Index> boundary_face;    ///< #S index into tet_boundary_faces(volume)
  std::vector<Tri> face_nodes;         ///< #S the face's tet-mesh node indices (outward counter-clockwise)
  std::vector<Vec3> weights;           ///< #S barycentric weights of face_nodes (each >= 0, sum 1)
  std::vector<double> rest_distance;   ///< #S initial |t_i - p_i| (mm), l_i of Figure 1
  std::vector<TrackingSide> side;      ///< #S side of the boundary the skin vertex starts on
  std::vector<TrackingMethod> method;  ///< #S how the tracking point was found

  std::size_t size() const { return boundary_face.size(); }
  /// Signed initial distance of connection i: positive outside the volume, negative inside (mm).
  double signed_rest_distance(std::size_t i) const {
    return side[i] == TrackingSide::inside ? -rest_distance[i] : rest_distance[i];
  }
};

/// Summary of a set of connections.
struct TrackingStats {
  std::size_t count = 0;
  std::size_t method_counts[tracking_method_count] = {0, 0, 0};  ///< indexed by TrackingMethod
  std::size_t inside_count = 0;                                  ///< skin vertices inside the volume
  double min_distance = 0.0;                                     ///< mm, over all connections (0 if none)
  double mean_distance = 0.0;                                    ///< mm
  double max_distance = 0.0;                                     ///< mm
  /// Fraction of connections found by a ray (either direction); 0 when there are none.
  double ray_fraction() const;
};

/// Connects every vertex of `skin` (#S vertices; its normals are used when present, else angle-weighted
/// vertex normals) to the boundary of `volume` (lengths in mm). Skin vertices outside the volume cast a ray
/// along -n_i that must enter the volume through an outward-facing boundary face; vertices inside cast
/// rays along -n_i and (option) +n_i that must leave it through a boundary face, and the nearer hit is
/// kept; a hit counts only within the maximum distance of `options`. Otherwise (or for a zero normal) the
/// closest boundary point is used, its side decided by the generalised winding number. The stored rest
/// distance is measured from the interpolated tracking point, so tracking_points() on the rest nodes gives
/// it back exactly. Parallel; the result does not depend on the thread count. Throws InputError for an
/// invalid skin or volume, or a volume without tets.
TrackingConnections compute_tracking(const TriMesh& skin, const TetMesh& volume, const TrackingOptions& options = {});

/// compute_tracking() with the volume's boundary already extracted: `boundary_faces` must be
/// tet_boundary_faces(volume) (extracting it sorts 4 faces per tet, the largest cost after the rays, so a
/// caller that keeps it, like make_body_model, saves doing it twice). Face node indices are range-checked.
TrackingConnections compute_tracking(const TriMesh& skin, const TetMesh& volume,
                                     const std::vector<TetFace>& boundary_faces, const TrackingOptions& options = {});

/// Tracking points t_i (#S) for node positions (#V, e.g. the deformed volume's): the barycentric
/// combination of each connection's face nodes. Throws InputError when a face node is out of range.
std::vector<Vec3> tracking_points(const TrackingConnections& tracking, const std::vector<Vec3>& node_positions);

/// Counts by method and side, and the min/mean/max rest distance (deterministic).
TrackingStats tracking_stats(const TrackingConnections& tracking);

/// Checks that every array has `skin_vertex_count` entries, faces and nodes are in range (given the
/// volume's `node_count` and `boundary_face_count`), weights are finite, non-negative (to 1e-9) and sum
/// to 1 (to 1e-9), distances finite and non-negative, sides and methods known. Throws InputError naming
/// `source` and the first bad connection ("tracking connection 17").
void validate_tracking(const TrackingConnections& tracking, std::size_t skin_vertex_count, std::size_t node_count,
                       std::size_t boundary_face_count, const std::string& source);

/// "ray -n", "ray +n" or "closest point".
const char* tracking_method_name(TrackingMethod method);

}  // namespace forensim
