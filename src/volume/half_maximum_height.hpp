#pragma once
/// The half-maximum height (HMH) threshold of a bright structure in a blurred volume: half-way between the value the
/// structure reaches inside and the value of what surrounds it. The scanner's blur spreads an edge over a voxel or
/// more; with a symmetric point-spread function the half-way value of a step lies on the step itself whatever the
/// voxel size, while a fixed iso-value does not (126 HU on a head CT with 3 mm voxels puts the bone surface a
/// millimetre or more outside the bone). The HMH is read off profiles across the edge where the structure is thick
/// enough to reach its own value (a plateau), and their mean is the threshold of the 3-D model.
/// (Spoor, Zonneveld and Macho, "Linear measurements of cortical bone and dental enamel by computed tomography:
/// applications and problems", Am. J. Phys. Anthropol. 91, 1993: the HMH protocol; Coleman and Colbert, "CT
/// thresholding protocols for taking measurements on three-dimensional models", Am. J. Phys. Anthropol. 133, 2007:
/// the mean of HMH values over many profiles as the threshold of a surface model.)

#include <cstddef>
#include <vector>

#include "geometry/tri_mesh.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

struct HalfMaximumOptions {
  /// Value of the iso-surface the profiles start from (stored volume units): above it is inside the structure.
  double iso_value = 0.0;
  /// How far inward (mm) the structure's peak is looked for, along the contiguous run above the iso-value.
  double peak_search_mm = 8.0;
  /// The surrounding level is the median of the profile from one to this many voxel extents outward of the iso
  /// crossing, where the edge's blur has died out (a voxel extent: the length of one voxel along the normal, so
  /// 3.2 mm across 3.2 mm voxels and 1.5 mm along 1.5 mm slices). At least 1.
  double background_voxels = 1.5;
  /// How far from the surface point (voxel extents) the profile's iso crossing may lie.
  double crossing_search_voxels = 1.0;
  /// Profiles whose peak is less than this far above the background (stored units) are not used.
  double min_contrast = 1.0;
  /// Profile sampling step, in voxel extents along the normal.
  double step_voxels = 0.1;
};

/// The profile of a volume along a surface point's outward normal around its iso crossing.
struct EdgeProfile {
  bool found = false;           ///< an iso crossing from inside to outside lies near the point, with contrast
  double peak = 0.0;            ///< highest value of the run above the iso-value, inward of the crossing
  double background = 0.0;      ///< median value one to background_voxels extents outward of the crossing
  double plateau_mm = 0.0;      ///< length of the run around the peak within 10 % of the contrast
  double edge_rise_mm = 0.0;    ///< distance over which the profile falls from 90 % to 10 % of the contrast
  double extent_mm = 0.0;       ///< one voxel's length along the normal
  double step_mm = 0.0;         ///< sample spacing
  double crossing_mm = 0.0;     ///< where the profile falls through the iso-value (mm along the normal)
  Vec3 outward = Vec3::Zero();  ///< the unit direction sampled
  std::vector<float> samples;   ///< values at t = (k - origin) * step_mm along `outward` (-inf outside the volume)
  int origin = 0;               ///< index of the sample at the point
  /// The peak is a plateau: flat (within 10 % of the contrast) over at least a voxel and at least the edge's own
  /// 90-10 % fall. A structure thinner than the blur is never flat for as long as its edges take to fall.
  bool is_plateau() const { return found && plateau_mm >= extent_mm && plateau_mm >= edge_rise_mm; }
  /// Half-way value between peak and background.
  double half_maximum() const { return 0.5 * (peak + background); }
  /// Where (mm along the normal, negative inward) the profile falls through `level` next to its iso crossing; NaN
  /// when it does not within the samples.
  double crossing_of(double level) const;
};

/// Samples `volume` along the unit vector `outward` through `point` and finds its iso crossing, peak and background.
EdgeProfile measure_edge_profile(const ScalarGrid& volume, const Vec3& point, const Vec3& outward,
                                 const HalfMaximumOptions& options);

/// The profiles of `volume` along the vertex normals of `surface` (an outward-oriented iso-surface of `volume` at
/// options.iso_value, world mm, with or without normals), one per vertex (not found where a normal is degenerate).
/// Measured once, they give both the threshold (half_maximum_height) and the moves (move_to_half_maximum).
/// Deterministic at any thread count. Throws InputError for a non-finite iso-value or options out of range.
std::vector<EdgeProfile> measure_edge_profiles(const TriMesh& surface, const ScalarGrid& volume,
                                               const HalfMaximumOptions& options);

/// The threshold measured on a surface.
struct HalfMaximumHeight {
  std::size_t profiles = 0;  ///< surface vertices whose profile was found
  std::size_t used = 0;      ///< of those, the ones averaged (with plateau_only, the plateaus: EdgeProfile::is_plateau;
                         ///< thinner structures never reach their own value, nor is their half-way value the edge's)
  double level = 0.0;     ///< mean half-maximum over the used profiles (stored units; 0 when none)
  double level_sd = 0.0;  ///< their standard deviation
  double peak = 0.0;      ///< mean peak and background of the used profiles
  double background = 0.0;
};

/// The HMH threshold of the structure whose surface `profiles` cross (measure_edge_profiles): the half-maximum of
/// the found profiles averaged, only the plateau ones with `plateau_only`.
HalfMaximumHeight half_maximum_height(const std::vector<EdgeProfile>& profiles, bool plateau_only = true);

/// What move_to_half_maximum did: moves are signed along the outward normal (negative: inward).
struct HalfMaximumMoves {
  std::size_t vertices = 0;  ///< vertices of the surface
  std::size_t to_level = 0;  ///< moved to the threshold's crossing (their peak reaches above it)
  std::size_t to_own = 0;    ///< thin: moved to the plate model's edge (their peak stays below the threshold)
  std::size_t capped = 0;    ///< moves cut to a voxel extent
  double mean_shift_mm = 0.0;
  double mean_abs_shift_mm = 0.0;
};

/// Moves every vertex of `surface` along the direction of its profile (`profiles`: measure_edge_profiles of this
/// surface) to the structure's edge: where its profile peaks above `level` (the half-maximum height threshold), to
/// where it falls through `level`; where the structure is too thin to reach it, to where it falls through the
/// thin_plate_level of its peak with `plateau` as the structure's own value (0: its own half-maximum). This keeps
/// thin structures an iso-surface at `level` would lose. Moves are cut to one voxel extent (the iso-surface already
/// lies within a voxel of the edge) and averaged over edge neighbours `smoothing_iterations` times (noise in one
/// profile should not crease the surface); normals are recomputed. Deterministic at any thread count. Throws
/// InputError for a non-finite level, negative iterations or a profile count other than the vertex count.
HalfMaximumMoves move_to_half_maximum(TriMesh& surface, const std::vector<EdgeProfile>& profiles, double level,
                                      double plateau, int smoothing_iterations = 4);

/// The level at the surfaces of a plate of value `plateau` (c) and any thickness d over `background` (b), blurred by a
/// Gaussian of any width s, given its blurred peak P = b + (c - b) erf(u), u = d / (2 sqrt 2 s): b + (c - b) erf(2u) /
/// 2 (the plate model of cortical-thickness mapping: Treece, Gee, Mayhew and Poole, "High resolution cortical bone
/// thickness measurement from clinical CT data", Med. Image Anal. 14, 2010). Above a thin plate's own half-maximum,
/// which lies outside it; the half-maximum (b + P) / 2 once P reaches c.
double thin_plate_level(double peak, double background, double plateau);

}  // namespace forensim
