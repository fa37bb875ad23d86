#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/primitives.hpp"
#include "render/quick_render.hpp"
#include "render/sheet.hpp"

using namespace forensim;

namespace {

int covered_pixels(const Image& image, const Vec4f& background) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) n += (image.rgba(x, y) - background).norm() > 0.02f ? 1 : 0;
  return n;
}

}  // namespace

TEST(Turntable, FramesShowTheSubjectFromDifferentSides) {
  Scene scene;
  scene.add(make_box_mesh(Vec3(-40, -10, -20), Vec3(40, 10, 20), 1), SurfaceMaterial::clay());
  RenderSettings settings;
  settings.width = 40;
  settings.height = 40;
  settings.samples_per_pixel = 1;
  const std::vector<Image> frames = render_turntable(scene, settings, 4, 0.0);
  ASSERT_EQ(frames.size(), 4u);
  // The box is long along X: wide from the front (0 degrees), narrow from the side (90 degrees), and the
  // same distance is used for every frame.
  const int front = covered_pixels(frames[0], settings.background);
  const int side = covered_pixels(frames[1], settings.background);
  EXPECT_GT(front, 2 * side);
  EXPECT_NEAR(covered_pixels(frames[2], settings.background), front, 0.1 * front);
  const std::vector<Image> named = render_turntable(scene, settings, {ViewName::front, ViewName::top});
  ASSERT_EQ(named.size(), 2u);
  EXPECT_GT(covered_pixels(named[0], settings.background), 100);
}

TEST(QuickRender, RendersAMeshFromANamedView) {
  RenderSettings settings;
  settings.width = 48;
  settings.height = 32;
  settings.samples_per_pixel = 1;
  TriMesh sphere = make_icosphere(Vec3::Zero(), 10, 2);
  const Image image = render_mesh(sphere, settings, "front");
  EXPECT_EQ(image.width(), 48);
  EXPECT_GT(covered_pixels(image, settings.background), 200);
  sphere.colors.assign(sphere.vertex_count(), Vec4f(0.9f, 0.05f, 0.05f, 1));
  const Image red = render_mesh(sphere, settings, "top");
  EXPECT_GT(red.at(24, 16, 0), red.at(24, 16, 1) + 0.2f);
  EXPECT_THROW(render_mesh(sphere, settings, "diagonal"), InputError);
}
