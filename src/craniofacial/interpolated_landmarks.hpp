#pragma once
/// Extra landmark pairs interpolated from the given ones where the soft tissue is near-constant (Kähler, Haber
/// and Seidel 2003, section 4.2, Figure 6a to 6b): with only about 40 landmarks the warp leaves skull areas
/// piercing the skin, so more pairs are generated on the upper and back part of the cranium and on the
/// mandible, each with an interpolated tissue thickness, never in the mid-face where thickness changes fast.
///
/// Two generators, run the same way on the template's skull and on the target skull so the points correspond:
/// - cranium cap: rays from the centre of the head frame spanned by glabella, opisthocranion and vertex (and
///   the zygia for the breadth), in directions given in that frame's normalised coordinates (azimuth around
///   the vertical, elevation above the g-op line: at least `cranium_min_elevation_front_deg` in front and
///   behind, `cranium_min_elevation_side_deg` at the sides, which keeps off the temporal muscles), meet the
///   outer skull; the depth is the inverse-distance-squared mean (in normalised frame coordinates) of the depths
///   at g, v and op;
/// - mandible arcs: points at equal steps along a path over the outer bone between two landmarks (mmb to
///   go and go to mr by default; the path walks the surface's tangent plane toward the far end and
///   is put back onto the surface by closest points), depth linear along it.
/// Each point's direction is the skull normal there: the skull's vertex normals (area-weighted means over each
/// vertex's ring of triangles) interpolated at the point.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

class RayCaster;

/// Landmarks on one skull as plain data: T-Table names ("g", "zy_L"), skull positions (mm) and depth vectors
/// d_i (mm; skin landmark = skull + d_i, eq. 1's q_i = s_i + d_i).
struct LandmarkDepths {
  std::vector<std::string> names;
  std::vector<Vec3> skull;
  std::vector<Vec3> depth_vectors;
};

/// Interior points between landmarks `from` and `to`.
struct LandmarkArc {
  std::string from, to;
  int count = 2;
};

/// The default mandible arcs: for each side X in {L, R}: mmb_X-go_X (2) and go_X-mr_X (1), along the lower
/// border and the ramus. Arcs from the chin's midline (me, pg) to mmb are left out: the surface path between
/// them turns under the jaw onto its inner (lingual) side, where no tissue depth is measured.
std::vector<LandmarkArc> default_mandible_arcs();

struct LandmarkInterpolationOptions {
  bool cranium = true;
  bool mandible = true;
  int cranium_rings = 4;     ///< elevation steps from the lowest elevation toward the vertex (plus the top point)
  int cranium_sectors = 16;  ///< azimuth steps around the vertical
  double cranium_min_elevation_front_deg = 15.0;
  double cranium_min_elevation_side_deg = 45.0;
  std::vector<LandmarkArc> mandible_arcs = default_mandible_arcs();
};

/// Generated points on one skull, in a fixed order for fixed options and landmark names.
struct InterpolatedLandmarks {
  std::vector<std::string> names;  ///< "cranium_r<ring>_s<sector>", "cranium_top", "<from>~<to>_<k>"
  std::vector<Vec3> skull;         ///< on the outer skull surface, mm
  std::vector<Vec3> normals;       ///< unit outward skull normals (patch averages)
  std::vector<double> depth_mm;    ///< interpolated tissue thickness
  /// Skin points skull + depth * normal (the warp's targets on a target skull).
  std::vector<Vec3> skin_targets() const;
};

/// Generates the points on `skull` (mm; its vertex normals are used when present, else computed), with
/// `skull_rays` built from it. The cranium cap needs "g", "v" and
/// "op" in `landmarks` (else it is skipped); an arc whose end is missing is skipped. Throws InputError for
/// inconsistent `landmarks` sizes, non-finite values or options out of range (rings and sectors in [1, 64],
/// elevations in [0, 89], arc counts in [1, 32]) or a ray caster of another mesh. Deterministic.
InterpolatedLandmarks interpolate_landmarks(const TriMesh& skull, const RayCaster& skull_rays,
                                            const LandmarkDepths& landmarks,
                                            const LandmarkInterpolationOptions& options = {});

/// The template's own skin points for interpolated skull points: where each point's normal ray first meets
/// `skin_rays` (within 100 mm), or skull + depth * normal when it misses.
std::vector<Vec3> skin_points_along_normals(const RayCaster& skin_rays, const InterpolatedLandmarks& points);

}  // namespace forensim
