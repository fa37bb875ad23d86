#pragma once
/// Per-frame texture maps of per-vertex skin data: when the skin mesh has UVs, the shaded vertex colours (or
/// any per-vertex scalar such as the moisture ratio) are interpolated with the barycentrics of each texel's
/// triangle and written into a map, the gutter dilated as texture/uv_bake.hpp's dilate_gutter() does. The UV
/// raster, each texel's three vertices and weights, and the dilation plan (which filled neighbours each gutter
/// texel averages, ring by ring) are computed once in the constructor, so a frame is one pass over the covered
/// texels and one over the gutter: the same maps as bake() with dilate_gutter(), without their per-frame setup.

#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"

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

  int resolution() const { return m_resolution; }
  std::size_t covered_texels() const { return m_texel_pixel.size(); }
  std::size_t gutter_texels() const { return m_gutter_pixel.size(); }

 private:
  template <int Channels, class Value>
  Image bake_values(const Value& value_at_vertex, PixelEncoding encoding) const;

  int m_resolution = 0;
  std::size_t m_vertices = 0;
  std::vector<std::size_t> m_texel_pixel;    ///< covered texel -> pixel index (y * resolution + x)
  std::vector<Tri> m_texel_vertices;         ///< covered texel -> its triangle's vertices
  std::vector<Vec3f> m_texel_weights;        ///< covered texel -> barycentric weights
  std::vector<std::size_t> m_gutter_pixel;   ///< gutter texels in dilation order (ring by ring)
  std::vector<std::size_t> m_gutter_offset;  ///< #gutter + 1: CSR offsets into m_gutter_source
  std::vector<std::size_t> m_gutter_source;  ///< pixel indices of the filled neighbours each averages
};

}  // namespace forensim
