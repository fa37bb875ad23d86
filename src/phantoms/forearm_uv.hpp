#pragma once
/// The `forearm-uv` phantom: the arm phantom's skin (right forearm and hand) as a uniform triangle mesh with
/// a clean UV layout for painting wounds and baking skin maps: no overlaps, low stretch, one texel density,
/// and seams where they are hard to see (underneath, along the palmar/ulnar sides, and around the cut end).
///
/// Layout (13 charts, each a topological disk; ids index ForearmUvModel::chart_names):
///   0 "cut"            the flat proximal cut end of the forearm (x = 0);
///   1 "dorsal"         upper skin of forearm, wrist and hand (smoothed normal z > -palmar_split);
///   2 "palmar"         the underside of forearm, wrist and hand;
///   3 + 2 d, 4 + 2 d   "<digit> dorsal" and "<digit> palmar" for d = 0..4: thumb, index, middle, ring, little
///                      (ArmPhantom::part_at), split by the plane through the digit's axis lowered by
///                      palmar_split radii, which halves the fingertip dome.
/// So the long seams run along the lower sides of forearm, hand and digits and under the fingertips; the rest
/// are the rim of the cut end and a loop around each digit's base. Digits get their own charts because a
/// finger's unrolled half is wider than the spacing of the fingers: kept on the hand chart they would overlap.
/// Frame as ArmPhantom: x distal, y radial, z dorsal (mm). The fingers are kept a little apart (see
/// make_forearm_uv()).

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

struct ForearmUvOptions {
  double voxel_mm = 1.5;  ///< grid spacing of the skin iso-surface (phantom_surface)
  double edge_mm = 2.0;   ///< target edge length of the isotropic remeshing
  int remesh_iterations = 3;
  /// Seam position: the dorsal chart takes every triangle whose smoothed normal has z > -palmar_split, so the
  /// side seams lie below the horizontal (0.3: about 17 degrees under the side lines).
  double palmar_split = 0.3;
  int seam_smoothing_iterations = 12;  ///< Laplacian smoothing of the normal-z field that places the seams
  int resolution = 2048;               ///< texture size the gutter is measured in
  int gutter_texels = 8;
};

/// Figures of the layout (see UvAtlasStats and UvChartStats in mesh_processing/uv_atlas.hpp).
struct ForearmUvStats {
  double l2_stretch = 1.0;  ///< global normalised L2 stretch (Sander et al. 2001)
  double max_chart_l2_stretch = 1.0;
  double area_distortion = 1.0;
  double packing_efficiency = 0.0;  ///< UV area of the triangles / unit square
  double mm_per_uv_unit = 0.0;      ///< common density; texel size = mm_per_uv_unit / resolution
  bool overlap_free = false;
  std::vector<double> chart_l2_stretch;  ///< per chart, in chart order
  std::vector<std::string> chart_flattening;
  double seam_length_mm = 0.0;           ///< total length of the edges between charts
  double hidden_seam_fraction = 0.0;     ///< share of the seam length that is hidden (see seam_is_hidden())
  std::size_t reassigned_triangles = 0;  ///< moved to another chart by the clean-up (islands, pinches)
};

struct ForearmUvModel {
  TriMesh mesh;                          ///< skin, mm, with vertex normals and corner UVs (triangle_uvs)
  std::vector<int> triangle_chart;       ///< #F chart index into chart_names
  std::vector<std::string> chart_names;  ///< "cut", "dorsal", "palmar", "thumb dorsal", ... "little palmar"
  ForearmUvStats stats;
  double seconds_surface = 0.0;  ///< time to mesh the skin
  double seconds_atlas = 0.0;    ///< time to build the atlas
};

/// Builds the forearm-uv phantom: phantom_surface(ArmPhantom, skin, voxel_mm) with the fingers kept apart
/// beyond the web (the arm SDF leaves 0.3 mm gaps that iso-surfacing would fuse into handles), then
/// remesh_isotropic(edge_mm); charts as above, cleaned so each is one connected disk with a smooth border
/// (islands, border spikes and notches, pinched vertices go to the neighbouring chart); then make_uv_atlas
/// (ARAP unless LSCM is valid where ARAP is not). Throws NumericError if the skin is not a sphere.
/// Deterministic. Throws InputError for options out of range (voxel_mm in [0.5, 5], edge_mm in [voxel_mm / 2,
/// 10], palmar_split in (-1, 1), resolution in [64, 16384]).
ForearmUvModel make_forearm_uv(const ForearmUvOptions& options = {});

/// Whether a point of the seam with (unit) surface normal `normal` is on a hidden side: facing palmar (z < 0),
/// or on the cut end rim (`on_cut_rim`). A seam drawn along the horizontal sides (z = 0) counts as visible.
bool seam_is_hidden(const Vec3& normal, bool on_cut_rim);

}  // namespace forensim
