#include "skin/skin_map_baker.hpp"

#include <string>

#include "core/error.hpp"

namespace forensim {

SkinMapBaker::SkinMapBaker(const TriMesh& skin, int resolution, int dilate_texels)
    : m_triangles(skin.triangles), m_vertices(skin.vertex_count()), m_dilate(dilate_texels) {
  require_input(skin.has_uvs(), "skin map baker", "skin", "mesh has no UVs");
  require_input(resolution >= 16 && resolution <= 8192, "skin map baker", "resolution", "must be in [16, 8192]");
  require_input(dilate_texels >= 0 && dilate_texels <= 64, "skin map baker", "dilate_texels", "must be in [0, 64]");
  m_raster = rasterize_uv(skin, resolution, resolution);
}

Image SkinMapBaker::bake_colours(const std::vector<Vec4f>& vertex_colours) const {
  require_input(
      vertex_colours.size() == m_vertices, "skin map baker", "vertex colours",
      "has " + std::to_string(vertex_colours.size()) + " entries for " + std::to_string(m_vertices) + " vertices");
  return bake(
      m_raster, 3,
      [&](const UvTexel& t) {
        const Tri& tri = m_triangles[static_cast<std::size_t>(t.triangle)];
        Vec4f c = Vec4f::Zero();
        for (int k = 0; k < 3; ++k)
          c += static_cast<float>(t.barycentric[k]) * vertex_colours[static_cast<std::size_t>(tri[k])];
        c[3] = 1.0f;
        return c;
      },
      m_dilate);
}

Image SkinMapBaker::bake_scalar(const std::vector<double>& vertex_values) const {
  require_input(
      vertex_values.size() == m_vertices, "skin map baker", "vertex values",
      "has " + std::to_string(vertex_values.size()) + " entries for " + std::to_string(m_vertices) + " vertices");
  return bake(
      m_raster, 1,
      [&](const UvTexel& t) {
        const Tri& tri = m_triangles[static_cast<std::size_t>(t.triangle)];
        double v = 0;
        for (int k = 0; k < 3; ++k) v += t.barycentric[k] * vertex_values[static_cast<std::size_t>(tri[k])];
        const float f = static_cast<float>(v);
        return Vec4f(f, f, f, 1.0f);
      },
      m_dilate, Vec4f(0, 0, 0, 0), PixelEncoding::data);
}

}  // namespace forensim
