#pragma once
/// Evaluation of a reconstruction against the real face (issue 8): on a CT that holds both skull and face, the
/// face is reconstructed from the skull alone and the real face (the CT's skin iso-surface) is measured against
/// the reconstructed skin over the face region, forehead to chin and ear to ear. The figures are those of the
/// craniofacial literature's surface comparisons: mean and RMS of the unsigned distance, the signed mean
/// (positive: the real face lies outside the reconstruction, i.e. the reconstruction is too thin there) and the
/// share of the surface within 2.5 mm (reported at 54 to 77 % for computerised reconstructions).
///
/// Distances are measured from the real face's vertices, each weighted by a third of the area of its triangles in
/// the region, to the closest point of the reconstructed skin (src/spatial ClosestPointQuery); the sign is that of
/// the offset along the reconstructed skin's interpolated vertex normal at that point.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craniofacial/head_frame.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/scan_field_of_view.hpp"
#include "geometry/tri_mesh.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

/// The real face of a CT: the skin iso-surface.
struct RealFaceOptions {
  /// Volume value at the skin surface. When not set: -524 HU, i.e. 500 for CT stored as HU + 1024 (the skin
  /// iso-value of VTK's medical examples); storage is taken as HU + 1024 when the volume has no value below -100.
  std::optional<double> skin_iso_value;
  int smoothing_iterations = 0;  ///< Taubin pairs on the iso-surface (0 = none)
};

/// The CT's skin: the largest component of its iso-surface (closed, outward, mm). Throws InputError naming
/// `source` when no voxel lies above the skin iso-value or the iso-value is not finite; `iso_used` receives the
/// value used when not null.
TriMesh real_face_surface(const ScalarGrid& volume, const std::string& source, const RealFaceOptions& options = {},
                          double* iso_used = nullptr);

/// The face region in the head frame, from skull landmarks (any vocabulary spelling): in front of the coronal
/// plane through the gonia (go_L, go_R; the tragi lie about above them), below the horizontal (Frankfort-parallel)
/// plane forehead_mm above glabella (g), above the mandibular plane through menton (me) and the gonia lowered by
/// chin_margin_mm (the soft tissue under the chin; the neck below it is left out).
struct FaceRegionOptions {
  double forehead_mm = 40.0;     ///< how far above glabella the forehead is measured
  double chin_margin_mm = 12.0;  ///< how far below the mandibular plane the chin's skin is measured
  double ear_margin_mm = 0.0;    ///< moves the coronal plane this far posterior of the gonia
};

struct FaceRegion {
  Plane coronal;   ///< normal posterior: the region lies on its negative side
  Plane forehead;  ///< normal superior: the region lies on its negative side
  Plane jaw;       ///< normal inferior-ish (away from the face): the region lies on its negative side
  /// True when `p` (mm) lies on the face side of all three planes.
  bool contains(const Vec3& p) const;
};

/// The region of `skull_landmarks` in `frame` (its axes give superior and posterior). Throws InputError naming
/// "face region" and the missing landmark when g, me, go_L or go_R is absent.
FaceRegion face_region(const LandmarkSet& skull_landmarks, const HeadFrame& frame,
                       const FaceRegionOptions& options = {});

struct FaceEvaluationOptions {
  double within_mm = 2.5;  ///< the tolerance of the within-share
  /// A real-face vertex counts only when a ray along its normal leaves the skin (so the nasal airway, the ear
  /// canal and other inner surfaces of the iso-surface are not measured); this far along the ray is ignored, mm.
  double exterior_ray_offset_mm = 1.0;
};

/// The figures and the per-vertex distances.
struct FaceEvaluation {
  double mean_abs_mm = 0.0;     ///< area-weighted mean of |d|
  double rms_mm = 0.0;          ///< area-weighted sqrt(mean d^2)
  double signed_mean_mm = 0.0;  ///< area-weighted mean of d (positive: the real face outside the reconstruction)
  double within_share = 0.0;    ///< share of the region's area with |d| <= within_mm, in [0, 1]
  double within_mm = 2.5;
  double max_abs_mm = 0.0;
  double p90_abs_mm = 0.0;       ///< area-weighted 90th percentile of |d|
  double area_mm2 = 0.0;         ///< area of the measured region
  std::size_t vertex_count = 0;  ///< real-face vertices measured
  /// Per real-face vertex: signed distance d (mm), NaN where not measured.
  std::vector<double> vertex_distance_mm;
  /// The measured part of the real face (its triangles in the region), with the vertex field "distance" (mm).
  TriMesh face;

  /// The figures as JSON (mean_abs_mm, rms_mm, signed_mean_mm, within_share, within_percent, within_mm,
  /// max_abs_mm, p90_abs_mm, area_mm2, vertex_count).
  nlohmann::json to_json() const;
};

/// Measures `real_skin` (mm, outward) against `reconstructed_skin` (mm, outward, the same frame) over `region`.
/// Triangles of the real skin are measured when their centroid lies in the region, they are not caps of `view`
/// (the scan's cuts), and at least one vertex is exterior. Throws InputError naming "real face" or
/// "reconstructed skin" for a mesh without triangles, and "face region" when no area of the real face lies in it.
FaceEvaluation evaluate_face(const TriMesh& real_skin, const TriMesh& reconstructed_skin, const FaceRegion& region,
                             const ScanFieldOfView& view = {}, const FaceEvaluationOptions& options = {});

}  // namespace forensim
