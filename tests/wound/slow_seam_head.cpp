// A wound painted across a UV seam of a real head scan (Lee Perry-Smith, CC BY 3.0, via three.js): with
// distances measured on the surface in 3D the wound is continuous across the seam; painted the thesis's way in
// UV space, the same dot stops at the seam.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/error.hpp"
#include "mesh_io/mesh_import.hpp"
#include "support/test_support.hpp"
#include "texture/uv_bake.hpp"
#include "wound/abrasion.hpp"
#include "wound/wound_canvas.hpp"

using namespace forensim;

namespace {
struct SeamEdge {
  Vec3 midpoint;
  Vec2 uv_a, uv_b;  // the midpoint's UV on either side, nudged into each side's triangle
};

// Edges whose two triangles give the shared vertices different UVs.
std::vector<SeamEdge> seam_edges(const TriMesh& mesh) {
  std::map<std::pair<Index, Index>, std::pair<std::size_t, int>> first;
  std::vector<SeamEdge> out;
  auto uv_mid = [&](std::size_t f, int k, double nudge) {
    const auto& tu = mesh.triangle_uvs[f];
    const Vec2 a = mesh.uvs[tu[k]], b = mesh.uvs[tu[(k + 1) % 3]], c = mesh.uvs[tu[(k + 2) % 3]];
    const Vec2 m = 0.5 * (a + b);
    return Vec2(m + nudge * (c - m));
  };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      Index v0 = mesh.triangles[f][k], v1 = mesh.triangles[f][(k + 1) % 3];
      const auto key = std::minmax(v0, v1);
      const auto it = first.find(key);
      if (it == first.end()) {
        first[key] = {f, k};
        continue;
      }
      const auto [g, j] = it->second;
      const Vec2 ua = uv_mid(g, j, 0.0), ub = uv_mid(f, k, 0.0);
      if ((ua - ub).norm() < 1e-3) continue;
      out.push_back({0.5 * (mesh.positions[v0] + mesh.positions[v1]), uv_mid(g, j, 0.02), uv_mid(f, k, 0.02)});
    }
  }
  return out;
}

float at_uv(const WoundCanvas& c, const Image& image, const Vec2& uv) {
  const Vec2 px = uv_to_pixel(uv, c.full_width, c.full_height);
  const int x = static_cast<int>(std::floor(px.x())) - c.region.x0;
  const int y = static_cast<int>(std::floor(px.y())) - c.region.y0;
  if (x < 0 || y < 0 || x >= c.width() || y >= c.height()) return -1.0f;
  return image.at(x, y);
}
}  // namespace

TEST(WoundSeam, HeadScanWoundIsContinuousAcrossAUvSeamOnTheSurface) {
  FORENSIM_REQUIRE_DATA(glb, "head-scan-lee-perry-smith/LeePerrySmith.glb");
  MeshImportOptions options;
  options.scale = 30.0;  // the scan is in arbitrary units; about 30 mm each gives a 26 cm head and neck
  const TriMesh mesh = import_mesh(glb, options);
  ASSERT_TRUE(mesh.has_uvs());
  const auto seams = seam_edges(mesh);
  ASSERT_FALSE(seams.empty());
  const int size = 1024;
  const UvRaster raster = rasterize_uv(mesh, size, size);
  // A seam edge whose texels on both sides show the edge itself (not a texel of an overlapping UV island),
  // away from the open neck border.
  auto shows = [&](const Vec2& uv, const Vec3& p) {
    const Vec2 px = uv_to_pixel(uv, size, size);
    const auto i = raster.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
    return i >= 0 && (raster.texels[static_cast<std::size_t>(i)].position - p).norm() < 1.0;
  };
  const SeamEdge* chosen = nullptr;
  for (std::size_t i = seams.size() / 2; i < seams.size() + seams.size() / 2 && !chosen; ++i) {
    const SeamEdge& s = seams[i % seams.size()];
    if (shows(s.uv_a, s.midpoint) && shows(s.uv_b, s.midpoint)) chosen = &s;
  }
  ASSERT_NE(chosen, nullptr);
  const SeamEdge& seam = *chosen;
  Image upper, lower;
  default_skin_maps(size, size, 1, upper, lower);
  WoundStroke dot;
  dot.points = {seam.midpoint};
  dot.radius_mm = 6.0;
  CanvasOptions o;
  o.reach_mm = AbrasionParams{}.reach_mm();
  const WoundCanvas surface = make_wound_canvas(mesh, raster, {dot}, upper, lower, o);
  // Both sides of the seam lie inside the wound, at nearly the same distance from its border.
  const float ia = at_uv(surface, surface.inside_mm, seam.uv_a), ib = at_uv(surface, surface.inside_mm, seam.uv_b);
  EXPECT_GT(ia, 3.0f);
  EXPECT_GT(ib, 3.0f);
  EXPECT_NEAR(ia, ib, 1.5f);
  // The thesis's way: the dot is painted around one side's UV only.
  o.distance = DistanceMode::uv;
  const WoundCanvas uv = make_wound_canvas(mesh, raster, {dot}, upper, lower, o);
  const float sa = at_uv(uv, uv.shape, seam.uv_a), sb = at_uv(uv, uv.shape, seam.uv_b);
  EXPECT_NE(sa >= 0.5f, sb >= 0.5f) << "the UV-space wound should stop at the seam";
}
