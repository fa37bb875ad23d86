// A wound painted across a UV seam of a real head scan (Lee Perry-Smith, CC BY 3.0, via three.js): with
// distances measured on the surface in 3D the wound is continuous across the seam; painted the thesis's way in
// UV space, the same dot stops at the seam.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "mesh_io/mesh_import.hpp"
#include "support/test_support.hpp"
#include "texture/uv_bake.hpp"
#include "texture/uv_seams.hpp"
#include "wound/abrasion.hpp"
#include "wound/wound_canvas.hpp"

using namespace forensim;

namespace {
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
  const auto seams = uv_seam_edges(mesh);
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
  const UvSeamEdge* chosen = nullptr;
  for (std::size_t i = seams.size() / 2; i < seams.size() + seams.size() / 2 && !chosen; ++i) {
    const UvSeamEdge& s = seams[i % seams.size()];
    if (shows(s.uv_a, s.midpoint) && shows(s.uv_b, s.midpoint)) chosen = &s;
  }
  ASSERT_NE(chosen, nullptr);
  const UvSeamEdge& seam = *chosen;
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
