// Baking per-vertex skin colours into UV maps: texels are the barycentric interpolation of the vertex values.

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "skin/skin_map_baker.hpp"
#include "texture/uv_bake.hpp"

using namespace forensim;

namespace {
TriMesh quad() {
  TriMesh q;
  q.positions = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  q.triangles = {{0, 1, 2}, {0, 2, 3}};
  q.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  q.triangle_uvs = q.triangles;
  compute_normals(q);
  return q;
}
}  // namespace

TEST(SkinMapBaker, InterpolatesVertexValuesAtTexels) {
  const TriMesh q = quad();
  const SkinMapBaker baker(q, 32, 2);
  EXPECT_EQ(baker.covered_texels(), 32u * 32u);
  // A value linear in position bakes to the same linear function of the texel centre.
  std::vector<double> values(4);
  for (std::size_t i = 0; i < 4; ++i) values[i] = 0.1 * q.positions[i][0] + 0.02 * q.positions[i][1];
  const Image map = baker.bake_scalar(values);
  ASSERT_EQ(map.channels(), 1);
  for (int y = 0; y < 32; y += 5)
    for (int x = 0; x < 32; x += 5) {
      const double u = (x + 0.5) / 32.0, v = 1.0 - (y + 0.5) / 32.0;
      EXPECT_NEAR(map.at(x, y), 0.1 * 10 * u + 0.02 * 10 * v, 1e-5) << x << " " << y;
    }
  std::vector<Vec4f> colours(4, Vec4f(0.3f, 0.2f, 0.1f, 1.0f));
  colours[2] = Vec4f(0.7f, 0.2f, 0.1f, 1.0f);
  const Image rgb = baker.bake_colours(colours);
  ASSERT_EQ(rgb.channels(), 3);
  // Vertex 2 (u = v = 1) has barycentric weight v in triangle (0, 1, 2) (u > v) and u in (0, 2, 3): min(u, v).
  for (int y = 0; y < 32; y += 3)
    for (int x = 0; x < 32; x += 3) {
      const double u = (x + 0.5) / 32.0, v = 1.0 - (y + 0.5) / 32.0;
      EXPECT_NEAR(rgb.at(x, y, 0), 0.3 + 0.4 * std::min(u, v), 1e-5) << x << " " << y;
      EXPECT_NEAR(rgb.at(x, y, 1), 0.2, 1e-6);
    }
}

TEST(SkinMapBaker, GutterMatchesTheTextureBaker) {
  TriMesh q = quad();
  q.uvs = {{0.2, 0.25}, {0.8, 0.25}, {0.8, 0.7}, {0.2, 0.7}};  // a gutter all around the chart
  const std::vector<Vec4f> colours = {
      {0.1f, 0.2f, 0.3f, 1}, {0.9f, 0.2f, 0.3f, 1}, {0.5f, 0.8f, 0.3f, 1}, {0.1f, 0.2f, 0.7f, 1}};
  const SkinMapBaker baker(q, 64, 5);
  EXPECT_GT(baker.gutter_texels(), 0u);
  const Image ours = baker.bake_colours(colours);
  const UvRaster raster = rasterize_uv(q, 64, 64);
  const Image reference = bake(
      raster, 3,
      [&](const UvTexel& t) {
        Vec4f c = Vec4f::Zero();
        for (int k = 0; k < 3; ++k)
          c += static_cast<float>(t.barycentric[k]) * colours[static_cast<std::size_t>(q.triangles[t.triangle][k])];
        return c;
      },
      5);
  ASSERT_EQ(ours.data().size(), reference.data().size());
  for (std::size_t i = 0; i < ours.data().size(); ++i) ASSERT_NEAR(ours.data()[i], reference.data()[i], 1e-6f) << i;
}

TEST(SkinMapBaker, RejectsMeshesWithoutUvsAndWrongSizes) {
  EXPECT_THROW(SkinMapBaker(make_icosphere(Vec3::Zero(), 1, 1), 64), InputError);
  const SkinMapBaker baker(quad(), 16);
  EXPECT_THROW(baker.bake_colours(std::vector<Vec4f>(3)), InputError);
  EXPECT_THROW(SkinMapBaker(quad(), 8), InputError);
}
