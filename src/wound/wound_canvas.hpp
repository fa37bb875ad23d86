#pragma once
/// The inputs every key position of a wound reads (Linnenbank 2015, chapter 3.2.1: "a binary input shape and
/// a hull"), prepared once per wound: the wound shape painted with strokes, the distance of every texel to the
/// wound's border in millimetres on the skin, the upper and lower skin colours, and the closing distance.
///
/// Beyond the thesis: shapes are unions of brush strokes (concave, several parts) unless the thesis's convex
/// hull is asked for, and distances are measured on the surface in 3D from the baked per-texel surface
/// positions, so a wound that crosses a UV seam stays continuous and is not stretched by the UV layout. The
/// thesis's way (distances in UV texels) stays available for comparison. Everything is computed in `region`,
/// the texel rectangle outside which every key position's maps equal the healthy skin.

#include <cstdint>
#include <limits>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"
#include "texture/uv_bake.hpp"
#include "wound/map_set.hpp"
#include "wound/tiled_map_set.hpp"

namespace forensim {

/// One brush stroke on the skin: a polyline of surface points (mm) painted with a round brush.
struct WoundStroke {
  std::vector<Vec3> points;  ///< >= 1 points on (or within a few mm of) the mesh, mm
  double radius_mm = 3.0;    ///< brush radius on the skin, mm
};

/// Where distances are measured.
enum class DistanceMode {
  surface,  ///< in 3D between baked surface positions (continuous across UV seams)
  uv,       ///< in UV texels / texels_per_mm, as the thesis does (breaks at seams, stretched by the layout)
};

/// How the wound shape is made from the strokes.
enum class ShapeMode {
  strokes,      ///< union of the brushed strokes (concave and multi-part shapes)
  convex_hull,  ///< the thesis's convex hull (Algorithm 4.1) of the strokes' UV points, filled (Algorithm 4.2)
};

struct CanvasOptions {
  DistanceMode distance = DistanceMode::surface;
  ShapeMode shape = ShapeMode::strokes;
  double reach_mm = 15.0;      ///< largest distance from the border any key position reads (glow thickness)
  double texels_per_mm = 0.0;  ///< texture density; 0 = from the mesh's UV density (mean over its area)
  std::uint64_t seed = 1;
};

/// What a tile of tiled_map_tile texels of a canvas holds, so key positions skip the tiles where their maps
/// equal the skin.
struct CanvasTile {
  std::size_t inside = 0;                                         ///< texels inside the wound
  float min_outside_mm = std::numeric_limits<float>::infinity();  ///< least outside_mm of its outside texels
  float max_inside_mm = 0.0f;                                     ///< largest inside_mm of its texels
  TexelRect inside_box;  ///< bounding box of its inside texels (region coordinates; empty when none)
};

struct WoundCanvas {
  int full_width = 0, full_height = 0;  ///< size of the whole texture
  TexelRect region;                     ///< texels where the wound's maps may differ from the skin
  double texels_per_mm = 1.0;           ///< texture density on the skin
  std::uint64_t seed = 1;
  Image upper_skin;  ///< RGBA linear, region size: healthy skin (the thesis's upper skin colour)
  Image lower_skin;  ///< RGBA linear, region size: skin under the epidermis (lower skin colour)
  Image shape;       ///< 1 channel, region size: 1 inside the wound, 0 outside
  Image outside_mm;  ///< 1 channel: outside texels' distance to the wound border (mm), 0 inside, +inf beyond reach
  Image inside_mm;   ///< 1 channel: inside texels' distance to the border (mm), 0 outside
  double closing_distance_mm = 0.0;  ///< Algorithm 4.3: the wound's diameter (mm)
  std::size_t wound_texels = 0;      ///< texels inside the shape
  TexelRect wound_box;               ///< bounding box of the shape's texels (region coordinates)
  DistanceMode distance = DistanceMode::surface;
  /// Per tile of the region (row-major, tiles of tiled_map_tile texels; see index_canvas_tiles).
  std::vector<CanvasTile> tiles;

  int width() const { return region.width(); }
  int height() const { return region.height(); }
};

/// Fills canvas.tiles from its shape and distances (make_wound_canvas does this; call it after building or
/// changing a canvas's maps by hand).
void index_canvas_tiles(WoundCanvas& canvas);

/// canvas.tiles when they match the region, else the same computed into `scratch`.
const std::vector<CanvasTile>& canvas_tiles(const WoundCanvas& canvas, std::vector<CanvasTile>& scratch);

/// Bounding box of the texels with channel 0 >= 0.5 (empty when there are none).
TexelRect shape_bounds(const Image& shape);

/// Mean texture density of a mesh with UVs at a width x height texture: sqrt(UV area in texels^2 / surface
/// area in mm^2). Throws InputError when the mesh has no UVs or zero area.
double mesh_texels_per_mm(const TriMesh& mesh_with_uvs, int width, int height);

/// Prepares the canvas of a wound painted with `strokes` on `mesh_with_uvs` rasterised in `raster`; the skin
/// maps are full-texture RGBA images of the raster's size (InputError otherwise). Throws InputError when the
/// strokes are empty, have a radius <= 0 or cover no texel.
WoundCanvas make_wound_canvas(const TriMesh& mesh_with_uvs, const UvRaster& raster,
                              const std::vector<WoundStroke>& strokes, const Image& upper_skin, const Image& lower_skin,
                              const CanvasOptions& options);

/// Simple procedural skin maps (RGBA linear) for meshes that come without them: an even upper skin tone and a
/// pinker, redder lower skin (dermis), each with faint seeded value noise.
void default_skin_maps(int width, int height, std::uint64_t seed, Image& upper_skin, Image& lower_skin);

/// Full-texture map set of healthy skin: colour = upper skin, reflection = `skin_reflection`, height 0.
MapSet skin_map_set(const Image& upper_skin, float skin_reflection);

}  // namespace forensim
