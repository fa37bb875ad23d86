#pragma once
/// UV atlases of skin meshes: charts given by the caller (one id per triangle) are flattened, brought to one
/// texel density and packed without overlap into the unit square, so procedural skin maps can be baked and
/// wounds painted into them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// How each chart is flattened, both with a free border.
enum class UvFlattening {
  lscm,       ///< least squares conformal maps (Levy et al. 2002, CGAL Surface_mesh_parameterization):
              ///< angle-preserving, fast, but shrinks narrow protrusions such as fingers
  arap,       ///< as-rigid-as-possible (Liu et al. 2008, local/global), started from LSCM: near-isometric
  automatic,  ///< ARAP, or LSCM where that folds or overlaps itself less or stretches less (ARAP only up to
              ///< arap_max_triangles); a chart is valid with no flipped triangle and no border crossing
};

struct UvAtlasOptions {
  UvFlattening flattening = UvFlattening::automatic;
  int resolution = 2048;                    ///< texels per side of the square texture the gutter is measured in
  int gutter_texels = 4;                    ///< empty texels between charts and from the atlas border
  int arap_iterations = 40;                 ///< ARAP local/global iterations
  std::size_t arap_max_triangles = 200000;  ///< automatic: larger charts use LSCM only
};

/// Distortion of one chart (Sander et al. 2001, "Texture mapping progressive meshes"), measured with the
/// chart's UVs scaled so its UV area equals its surface area: 1 is an isometry.
struct UvChartStats {
  int chart = 0;  ///< the caller's chart id
  std::size_t triangle_count = 0;
  double area_mm2 = 0.0;              ///< surface area
  double l2_stretch = 1.0;            ///< area-weighted RMS of the per-triangle L2 stretch, normalised
  double max_stretch = 1.0;           ///< largest per-triangle L-infinity stretch (largest singular value), normalised
  double area_distortion = 1.0;       ///< area-weighted mean of max(r, 1/r), r = normalised UV/surface area ratio
  std::string flattening;             ///< "lscm" or "arap"
  std::size_t flipped_triangles = 0;  ///< triangles with non-positive UV area (0 for a valid chart)
  /// Pairs of border edges that cross plus vertices the triangles wind around more than once: where the chart
  /// overlaps itself (0 when valid).
  std::size_t self_overlaps = 0;
};

/// The whole atlas.
struct UvAtlasStats {
  double l2_stretch = 1.0;  ///< global normalised L2 stretch over all triangles (Sander et al. 2001)
  double max_chart_l2_stretch = 1.0;
  double area_distortion = 1.0;     ///< as in UvChartStats, over all triangles
  double packing_efficiency = 0.0;  ///< UV area covered by triangles / area of [0,1]^2
  double mm_per_uv_unit = 0.0;      ///< the common density: one UV unit is this many mm on every chart
  bool overlap_free = false;        ///< uv_triangles_overlap() found no overlap at 2 * resolution
  std::size_t seam_edge_count = 0;  ///< mesh edges whose two triangles lie in different charts
};

struct UvAtlas {
  TriMesh mesh;                      ///< the input with uvs/triangle_uvs (one UV per vertex and chart)
  std::vector<int> triangle_chart;   ///< #F the caller's chart ids
  std::vector<UvChartStats> charts;  ///< one per distinct chart id, in increasing id order
  UvAtlasStats stats;
};

/// Triangles across each edge of each triangle of `mesh` (#F, edge k joins corners k and k+1; -1 on a border
/// or a non-manifold edge).
std::vector<std::array<std::int32_t, 3>> triangle_edge_neighbours(const TriMesh& mesh);

/// Chart clean-up before flattening: every edge-connected piece of a chart (#F labels in `triangle_chart`)
/// other than its largest moves to the chart it shares most edges with. Returns the triangles moved.
std::size_t merge_chart_islands(const std::vector<std::array<std::int32_t, 3>>& neighbours,
                                std::vector<int>& triangle_chart);

/// Flattens and packs the charts of `mesh` (welded, manifold, consistently oriented; lengths in mm).
/// `triangle_chart` gives a chart id (any non-negative int) per triangle; each chart must be a topological
/// disk: edge-connected, manifold, one boundary loop and Euler characteristic V - E + F = 1, else InputError
/// naming the chart. Charts are flattened (options.flattening), scaled to the same mm per UV unit, rotated
/// to their minimum-area bounding rectangle and shelf-packed into [0,1]^2 with options.gutter_texels empty
/// texels (at options.resolution) between charts and from the border. Vertices are not duplicated: a
/// vertex on a seam gets one UV per chart through mesh.triangle_uvs. Every UV triangle keeps the
/// orientation of its surface triangle (counter-clockwise, positive area).
UvAtlas make_uv_atlas(const TriMesh& mesh, const std::vector<int>& triangle_chart, const UvAtlasOptions& options = {});

/// Normalised global L2 stretch of a mesh with UVs (Sander et al. 2001): sqrt(sum(L2_t^2 A_t) / sum(A_t)) times
/// sqrt(sum(A'_t) / sum(A_t)), A surface and A' UV areas. 1 for an isometry up to scale. Triangles with zero
/// UV area count as infinite stretch.
double uv_l2_stretch(const TriMesh& mesh_with_uvs);

/// Texels of a `resolution` x `resolution` grid over [0,1]^2 whose centre lies strictly inside more than one
/// UV triangle (exact up to the texel grid: two triangles that share an edge never count). Texels outside the
/// unit square are not counted; a UV outside [0,1]^2 is reported by uv_outside_unit_square().
std::size_t uv_overlap_texels(const TriMesh& mesh_with_uvs, int resolution);

/// True when uv_overlap_texels(mesh_with_uvs, resolution) > 0.
bool uv_triangles_overlap(const TriMesh& mesh_with_uvs, int resolution = 4096);

/// Number of UVs outside [margin, 1 - margin]^2.
std::size_t uv_outside_unit_square(const TriMesh& mesh_with_uvs, double margin = 0.0);

}  // namespace forensim
