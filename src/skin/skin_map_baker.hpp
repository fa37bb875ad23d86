#pragma once
/// Per-frame texture maps of per-vertex skin data: when the skin mesh has UVs, the shaded vertex colours (or
/// any per-vertex scalar such as the moisture ratio) are interpolated with the barycentrics of each texel's
/// triangle and written into a map, the gutter dilated (texture/uv_bake.hpp). The UV raster is computed once
/// in the constructor, so a frame costs one pass over the covered texels.

#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"
#include "texture/uv_bake.hpp"

namespace forensim {

class SkinMapBaker {
 public:
  /// Rasterises the UVs of `skin` at resolution x resolution texels, keeping `dilate_texels` rings of gutter.
  /// Throws InputError when the mesh has no UVs or for a resolution outside [16, 8192].
  SkinMapBaker(const TriMesh& skin, int resolution, int dilate_texels = 4);

  /// RGB map (linear colour, written sRGB-encoded) of #V linear RGBA vertex colours.
  Image bake_colours(const std::vector<Vec4f>& vertex_colours) const;
  /// One-channel data map of #V values.
  Image bake_scalar(const std::vector<double>& vertex_values) const;

  int resolution() const { return m_raster.width; }
  std::size_t covered_texels() const { return m_raster.texels.size(); }

 private:
  std::vector<Tri> m_triangles;
  std::size_t m_vertices = 0;
  UvRaster m_raster;
  int m_dilate = 4;
};

}  // namespace forensim
