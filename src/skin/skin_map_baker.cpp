#include "skin/skin_map_baker.hpp"

#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/uv_bake.hpp"

namespace forensim {

SkinMapBaker::SkinMapBaker(const TriMesh& skin, int resolution, int dilate_texels)
    : m_resolution(resolution), m_vertices(skin.vertex_count()) {
  require_input(skin.has_uvs(), "skin map baker", "skin", "mesh has no UVs");
  require_input(resolution >= 16 && resolution <= 8192, "skin map baker", "resolution", "must be in [16, 8192]");
  require_input(dilate_texels >= 0 && dilate_texels <= 64, "skin map baker", "dilate_texels", "must be in [0, 64]");
  const UvRaster raster = rasterize_uv(skin, resolution, resolution);
  const auto w = static_cast<std::size_t>(resolution);
  m_texel_pixel.reserve(raster.texels.size());
  m_texel_vertices.reserve(raster.texels.size());
  m_texel_weights.reserve(raster.texels.size());
  for (const UvTexel& t : raster.texels) {
    m_texel_pixel.push_back(static_cast<std::size_t>(t.y) * w + static_cast<std::size_t>(t.x));
    m_texel_vertices.push_back(skin.triangles[static_cast<std::size_t>(t.triangle)]);
    m_texel_weights.push_back(t.barycentric.cast<float>());
  }
  // The dilation plan of dilate_gutter(): ring by ring, each unfilled texel with filled 8-neighbours takes their
  // mean (neighbours in the same dy, dx order, so the float sums are the same).
  std::vector<std::uint8_t> filled = coverage(raster), next = filled;
  m_gutter_offset.push_back(0);
  for (int ring = 0; ring < dilate_texels; ++ring) {
    for (int y = 0; y < resolution; ++y)
      for (int x = 0; x < resolution; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
        if (filled[i]) continue;
        const std::size_t first = m_gutter_source.size();
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= resolution || yy >= resolution) continue;
            const std::size_t j = static_cast<std::size_t>(yy) * w + static_cast<std::size_t>(xx);
            if (filled[j]) m_gutter_source.push_back(j);
          }
        if (m_gutter_source.size() == first) continue;
        m_gutter_pixel.push_back(i);
        m_gutter_offset.push_back(m_gutter_source.size());
        next[i] = 1;
      }
    filled = next;
  }
}

template <int Channels, class Value>
Image SkinMapBaker::bake_values(const Value& value_at_vertex, PixelEncoding encoding) const {
  Image image(m_resolution, m_resolution, Channels, 0.0f, encoding);
  float* data = image.data().data();
  parallel_for_chunks(0, m_texel_pixel.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const Tri& tri = m_texel_vertices[t];
      const Vec3f& b = m_texel_weights[t];
      float* p = data + m_texel_pixel[t] * Channels;
      for (int c = 0; c < Channels; ++c)
        p[c] =
            b[0] * value_at_vertex(tri[0], c) + b[1] * value_at_vertex(tri[1], c) + b[2] * value_at_vertex(tri[2], c);
    }
  });
  // Gutter texels in plan order: every source was covered or filled by an earlier ring.
  for (std::size_t g = 0; g < m_gutter_pixel.size(); ++g) {
    float sum[Channels] = {};
    for (std::size_t k = m_gutter_offset[g]; k < m_gutter_offset[g + 1]; ++k)
      for (int c = 0; c < Channels; ++c) sum[c] += data[m_gutter_source[k] * Channels + c];
    const auto n = static_cast<float>(m_gutter_offset[g + 1] - m_gutter_offset[g]);
    for (int c = 0; c < Channels; ++c) data[m_gutter_pixel[g] * Channels + c] = sum[c] / n;
  }
  return image;
}

Image SkinMapBaker::bake_colours(const std::vector<Vec4f>& vertex_colours) const {
  require_input(
      vertex_colours.size() == m_vertices, "skin map baker", "vertex colours",
      "has " + std::to_string(vertex_colours.size()) + " entries for " + std::to_string(m_vertices) + " vertices");
  return bake_values<3>([&](Index v, int c) { return vertex_colours[static_cast<std::size_t>(v)][c]; },
                        PixelEncoding::linear);
}

Image SkinMapBaker::bake_scalar(const std::vector<double>& vertex_values) const {
  require_input(
      vertex_values.size() == m_vertices, "skin map baker", "vertex values",
      "has " + std::to_string(vertex_values.size()) + " entries for " + std::to_string(m_vertices) + " vertices");
  return bake_values<1>([&](Index v, int) { return static_cast<float>(vertex_values[static_cast<std::size_t>(v)]); },
                        PixelEncoding::data);
}

}  // namespace forensim
