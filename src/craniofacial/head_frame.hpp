#pragma once
/// The head's anatomical frame: the Frankfort horizontal (the plane through both porions and the left
/// orbitale, the standard orientation of skulls in craniometry and of the paper's frontal views) and the
/// midsagittal plane (from midline and paired landmarks, or the mirror-symmetry plane fitted to the skull
/// mesh). Landmark definitions such as "most anterior", "highest" or "most lateral" are read in this frame,
/// and the nose and mouth guides are placed in its frontal view.

#include <optional>
#include <string>

#include "core/types.hpp"
#include "craniofacial/landmark_set.hpp"
#include "geometry/tri_mesh.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {

/// A plane {p : normal . (p - point) = 0}; `normal` is unit length.
struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  /// Signed distance of `p` from the plane (positive on the normal's side), mm.
  double signed_distance(const Vec3& p) const { return normal.dot(p - point); }
  /// Mirror image of `p` in the plane.
  Vec3 reflect(const Vec3& p) const { return p - 2.0 * signed_distance(p) * normal; }
  /// Projection of `p` onto the plane.
  Vec3 project(const Vec3& p) const { return p - signed_distance(p) * normal; }
};

/// The Frankfort horizontal through porion_L, porion_R and orbitale_L ("po_L", "po_R", "or_L"; orbitale_R is
/// used when the left one is missing), normal pointing superior: anterior x (po_L - po_R), with anterior the
/// direction from the porions' midpoint to orbitale. Throws InputError naming the set when a landmark is
/// missing or the three are (nearly) collinear.
Plane frankfort_plane(const LandmarkSet& skull_landmarks);

/// The midsagittal plane from landmarks: its normal is the mean of the unit vectors from right to left
/// landmark of every bilateral pair present (e.g. po_R -> po_L), and it passes through the mean of the pairs'
/// midpoints and the midline landmarks. Without pairs, the least-squares plane through at least three midline
/// landmarks, its normal pointed towards +x (LPS left). Names are read through the built-in vocabulary; names it
/// does not know are skipped. Throws InputError when neither is possible.
Plane midsagittal_plane(const LandmarkSet& skull_landmarks);

struct SymmetryPlaneOptions {
  int max_iterations = 50;
  std::size_t max_samples = 5000;  ///< vertices used (every k-th vertex when the mesh has more)
  double trim_fraction = 0.2;      ///< share of worst-matched pairs dropped each iteration (asymmetries, damage)
  double tolerance_mm = 1e-4;      ///< stop when the plane moves less than this (offset and normal x size)
};

/// Result of the symmetry-plane fit.
struct SymmetryPlaneFit {
  Plane plane;
  int iterations = 0;
  double rms_mm = 0.0;  ///< RMS distance from mirrored sample vertices to the mesh at the fitted plane (kept pairs)
};

/// The mirror-symmetry plane of a mesh, refined from `initial` (e.g. the landmark midsagittal plane) by
/// point-to-plane iterated closest points: every sample vertex v is mirrored, the closest mesh point c and its
/// face normal m are found, the worst `trim_fraction` of pairs dropped (asymmetries, damage), and a Gauss-Newton
/// step on the plane's normal and offset reduces sum (m . (mirror(v) - c))^2; repeated until the plane moves
/// less than the tolerance. Deterministic (batch queries keep their order). Throws InputError for an empty mesh.
SymmetryPlaneFit fit_symmetry_plane(const TriMesh& mesh, const Plane& initial,
                                    const SymmetryPlaneOptions& options = {});
/// As above on a prebuilt closest-point query of `mesh` (ClosestPointQuery(mesh)), for several fits on one mesh
/// without rebuilding its BVH each time. Same result.
SymmetryPlaneFit fit_symmetry_plane(const TriMesh& mesh, const ClosestPointQuery& query, const Plane& initial,
                                    const SymmetryPlaneOptions& options = {});

/// Right-handed anatomical frame in LPS orientation: x towards the subject's left, y posterior, z superior.
struct HeadFrame {
  Vec3 origin = Vec3::Zero();         ///< porions' midpoint moved along x onto the midsagittal plane (world mm)
  Mat3 axes = Mat3::Identity();       ///< columns: the frame's x, y, z in world coordinates
  Plane frankfort;                    ///< z = 0 of the frame
  Plane midsagittal;                  ///< as given (x = 0 of the frame up to its tilt against the Frankfort plane)
  double perpendicularity_deg = 0.0;  ///< how far the two planes are from perpendicular

  /// Head coordinates of a world point.
  Vec3 to_head(const Vec3& world) const { return axes.transpose() * (world - origin); }
  /// World position of head coordinates.
  Vec3 to_world(const Vec3& head) const { return origin + axes * head; }
  /// The affine map world -> head.
  Eigen::Affine3d world_to_head() const;
};

/// The frame of a Frankfort plane and a midsagittal plane: z = the Frankfort normal (superior), x = the
/// midsagittal normal made perpendicular to z and pointed towards po_L, y = z x x (posterior). Needs po_L and
/// po_R in `skull_landmarks` (origin and the left side). Throws InputError when the planes are nearly parallel.
HeadFrame head_frame(const Plane& frankfort, const Plane& midsagittal, const LandmarkSet& skull_landmarks);
/// head_frame(frankfort_plane(l), midsagittal_plane(l), l).
HeadFrame head_frame_from_landmarks(const LandmarkSet& skull_landmarks);
/// The frame with the skull's own symmetry plane: the Frankfort plane from the landmarks, the midsagittal plane
/// fitted to `skull` (fit_symmetry_plane) from the landmarks' midsagittal plane. For skulls whose landmarks are
/// few or placed roughly; the fit's RMS is returned through `fit` when not null.
HeadFrame head_frame_from_skull(const TriMesh& skull, const LandmarkSet& skull_landmarks,
                                const SymmetryPlaneOptions& options = {}, SymmetryPlaneFit* fit = nullptr);

}  // namespace forensim
