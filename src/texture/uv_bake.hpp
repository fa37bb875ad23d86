#pragma once
/// Baking from a surface into its UV maps: which triangle covers each texel, where that texel lies on the
/// surface (mm), its normal and tangent frame, then maps evaluated per texel (procedural skin, painted
/// wounds) with the background gutter filled by dilation so mip-mapping does not bleed it in.
///
/// Texel convention (as forensim::Image): texel (x, y) has its centre at u = (x + 0.5) / width,
/// v = 1 - (y + 0.5) / height (rows top to bottom, v up as in OBJ and OpenGL).

#include <cstdint>
#include <functional>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"

namespace forensim {

/// A texel covered by a UV triangle and the surface point it shows.
struct UvTexel {
  int x = 0, y = 0;    ///< texel column and row
  Index triangle = 0;  ///< covering triangle
  Vec3 barycentric;    ///< weights of the triangle's corners 0, 1, 2 at the texel centre (sum 1)
  Vec3 position;       ///< surface point, mm
  Vec3 normal;         ///< unit interpolated vertex normal (face normal when the mesh has none)
  Vec3 tangent;        ///< unit, along increasing u, orthogonal to `normal`
  Vec3 bitangent;      ///< unit, along increasing v: normal x tangent, or its negative where the UVs are mirrored
  bool inside = true;  ///< false for a padding texel: outside every triangle, barycentrics extrapolated
};

/// The texels of a width x height map that UV triangles cover.
struct UvRaster {
  int width = 0, height = 0;
  std::vector<UvTexel> texels;    ///< covered texels, row by row (y then x)
  std::vector<std::int32_t> map;  ///< width * height: index into texels, or -1 where no triangle covers the centre
  /// Index into texels of texel (x, y), or -1.
  std::int32_t at(int x, int y) const {
    return map[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

/// Per-triangle tangent and bitangent from the UV derivatives (dP/du, dP/dv; Lengyel 2001), not normalised.
/// Zero vectors for a triangle with zero UV area.
void triangle_tangents(const TriMesh& mesh_with_uvs, Index triangle, Vec3& dp_du, Vec3& dp_dv);

/// Rasterises the UV triangles of `mesh_with_uvs` at their texel centres (a centre on a shared edge goes to the
/// lower triangle index; overlapping triangles likewise) and interpolates positions and normals there.
/// The tangent frame is per triangle, Gram-Schmidt orthogonalised against the interpolated normal (as
/// MikkTSpace does per vertex). `padding_texels` rings of texels around the covered ones are added with
/// inside = false: each takes the neighbouring texel's triangle that it lies least outside of, with the
/// position extrapolated on that triangle's plane, so that a procedural (solid) bake is exact up to the
/// chart borders and bilinear lookups there read no blend (keep it below half the atlas gutter).
/// Deterministic; parallel over texels. Throws InputError when the mesh has no UVs, for sizes outside
/// [1, 16384] or padding outside [0, 64].
UvRaster rasterize_uv(const TriMesh& mesh_with_uvs, int width, int height, int padding_texels = 0);

/// Fills up to `texels` rings of uncovered texels around the covered ones with the mean of their already
/// filled 8-neighbours, ring by ring (deterministic). `covered` is width * height flags (non-zero = baked).
void dilate_gutter(Image& image, const std::vector<std::uint8_t>& covered, int texels);

/// Flags of the raster's texels (1 for covered and padding texels), for dilate_gutter().
std::vector<std::uint8_t> coverage(const UvRaster& raster);

/// Evaluates `shader` at every covered texel in parallel into an image of `channels` (1..4; an RGBA value is
/// converted as by Image::set_rgba), `background` elsewhere, then dilates `dilate_texels` rings into the
/// gutter. The shader must be thread-safe and depend only on its texel (then the map is deterministic).
Image bake(const UvRaster& raster, int channels, const std::function<Vec4f(const UvTexel&)>& shader,
           int dilate_texels = 4, const Vec4f& background = Vec4f(0, 0, 0, 0),
           PixelEncoding encoding = PixelEncoding::linear);

/// UV at barycentric coordinates of a triangle (for strokes found by a ray cast: triangle, barycentrics -> UV).
Vec2 uv_at(const TriMesh& mesh_with_uvs, Index triangle, const Vec3& barycentric);

/// Continuous pixel coordinates (x right, y down, centres at i + 0.5) of a UV in a width x height image.
Vec2 uv_to_pixel(const Vec2& uv, int width, int height);

}  // namespace forensim
