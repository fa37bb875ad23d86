#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/primitives.hpp"
#include "render/renderer.hpp"

using namespace forensim;

namespace {

// A scene lit by one hard directional light and no environment, drawn without tone curve.
Scene plain_scene() {
  Scene scene;
  scene.lights.clear();
  scene.environment.intensity = 0.0;
  return scene;
}

RenderSettings small_settings(int size = 64, int spp = 4) {
  RenderSettings settings;
  settings.width = size;
  settings.height = size;
  settings.samples_per_pixel = spp;
  settings.tone_map = ToneMap::linear;
  settings.background = Vec4f(0, 0, 0, 1);
  return settings;
}

SurfaceMaterial matte(const Vec3f& colour) {
  SurfaceMaterial m;
  m.base_colour = colour;
  m.specular = 0.0;
  return m;
}

}  // namespace

TEST(Renderer, SphereLitFromTheLeftIsBrighterOnTheLeft) {
  Scene scene = plain_scene();
  scene.add(make_icosphere(Vec3::Zero(), 50, 3), matte(Vec3f(0.8f, 0.8f, 0.8f)));
  scene.camera = Camera::look_at(Vec3(0, -400, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  scene.lights.push_back(Light::directional(-scene.camera.right(), 1.0, 0.0));
  const Image image = render(scene, small_settings());
  double left = 0, right = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 32; ++x) {
      left += image.at(x, y, 0);
      right += image.at(63 - x, y, 0);
    }
  EXPECT_GT(left, 5.0 * right + 1.0);
}

TEST(Renderer, CutAwayRemovesExactlyThePositiveHalfAndRevealsTheInside) {
  const auto count_green = [](const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        if (image.at(x, y, 1) > image.at(x, y, 0) + 0.05f) ++n;
    return n;
  };
  Scene scene = plain_scene();
  scene.add(make_icosphere(Vec3::Zero(), 50, 3), matte(Vec3f(0.8f, 0.1f, 0.1f)), "outer");
  scene.add(make_icosphere(Vec3::Zero(), 25, 2), matte(Vec3f(0.1f, 0.8f, 0.1f)), "inner");
  scene.camera = Camera::orthographic(Vec3(0, -400, 0), Vec3::Zero(), Vec3::UnitZ(), 120);
  scene.lights.push_back(Light::directional(Vec3(0.3, -1, 0.4), 1.0, 0.0));
  const RenderSettings settings = small_settings();
  EXPECT_EQ(count_green(render(scene, settings)), 0);

  // Remove the half facing the camera: the inner sphere shows (as its cross-section cap).
  scene.cutaway = CutPlane{Vec3::Zero(), Vec3(0, -1, 0)};
  EXPECT_GT(count_green(render(scene, settings)), 100);

  // Remove x > 0, seen from the front: nothing right of the image centre (pixels 32..63) remains.
  scene.cutaway = CutPlane{Vec3::Zero(), Vec3(1, 0, 0)};
  const Image half = render(scene, settings);
  int right_covered = 0, left_covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool covered = half.at(x, y, 0) + half.at(x, y, 1) > 0.02f;
      (x < 32 ? left_covered : right_covered) += covered ? 1 : 0;
    }
  EXPECT_EQ(right_covered, 0);
  EXPECT_GT(left_covered, 600);
}

TEST(Renderer, HalfOpaqueOverlayShowsTheObjectBehind) {
  Scene scene = plain_scene();
  scene.add(make_icosphere(Vec3(0, 60, 0), 40, 3), matte(Vec3f(0.9f, 0.05f, 0.05f)), "behind");
  scene.add(make_box_mesh(Vec3(-30, -30, -30), Vec3(30, 0, 30), 1), matte(Vec3f(0.05f, 0.05f, 0.9f)), "front");
  scene.camera = Camera::look_at(Vec3(0, -400, 0), Vec3(0, 0, 0), Vec3::UnitZ(), 20);
  scene.lights.push_back(Light::directional(Vec3(0, -1, 0.2), 1.0, 0.0));
  const RenderSettings settings = small_settings();
  const Image opaque = render(scene, settings);  // sRGB-encoded values
  EXPECT_LT(opaque.at(32, 32, 0), 0.3f);
  EXPECT_GT(opaque.at(32, 32, 2), 0.8f);
  scene.objects[1].material.opacity = 0.5;
  const Image half = render(scene, settings);
  EXPECT_GT(half.at(32, 32, 0), opaque.at(32, 32, 0) + 0.1f);  // the red sphere shows through the box
  EXPECT_GT(half.at(32, 32, 2), 0.5f);                         // and the box is still there
  // Fully transparent: only the sphere.
  scene.objects[1].material.opacity = 0.0;
  const Image none = render(scene, settings);
  EXPECT_GT(none.at(32, 32, 0), half.at(32, 32, 0));
}

TEST(Renderer, IdenticalAtOneAndTwoThreads) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 50, 3), SurfaceMaterial::skin());
  scene.add(make_box_mesh(Vec3(-80, -80, -70), Vec3(80, 80, -50), 1), SurfaceMaterial::clay());
  scene.frame(ViewName::three_quarter, 1.0);
  RenderSettings settings = small_settings(48, 5);
  settings.tone_map = ToneMap::aces;
  set_thread_count(1);
  const Image one = render(scene, settings);
  set_thread_count(2);
  const Image two = render(scene, settings);
  set_thread_count(0);
  ASSERT_EQ(one.data().size(), two.data().size());
  EXPECT_TRUE(one.data() == two.data());
  // A different seed changes the noise.
  settings.seed = 2;
  EXPECT_FALSE(render(scene, settings).data() == one.data());
}

TEST(Renderer, RejectsInvalidObjectsAndSettings) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 1, 1), SurfaceMaterial::field("moisture", 0, 1));
  EXPECT_THROW(Renderer{scene}, InputError);
  scene.objects[0].material = SurfaceMaterial::clay();
  scene.objects[0].material.colour_source = ColourSource::texture;
  scene.objects[0].material.base_texture = std::make_shared<const Image>(2, 2, 3, 1.0f);
  EXPECT_THROW(Renderer{scene}, InputError);  // no UVs
  scene.objects[0].material = SurfaceMaterial::clay();
  scene.objects[0].material.opacity = 2.0;
  EXPECT_THROW(Renderer{scene}, InputError);
  scene.objects[0].material.opacity = 1.0;
  RenderSettings settings = small_settings();
  settings.samples_per_pixel = 0;
  EXPECT_THROW(render(scene, settings), InputError);
  TriMesh bad = make_icosphere(Vec3::Zero(), 1, 0);
  bad.triangles[0][0] = 1000;
  scene.add(bad, SurfaceMaterial::clay());
  EXPECT_THROW(Renderer{scene}, InputError);
}

TEST(Renderer, TransparentBackgroundHasCoverageAlpha) {
  Scene scene = plain_scene();
  scene.add(make_icosphere(Vec3::Zero(), 50, 3), matte(Vec3f(0.5f, 0.5f, 0.5f)));
  scene.camera = Camera::look_at(Vec3(0, -400, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  RenderSettings settings = small_settings();
  settings.background = Vec4f(0, 0, 0, 0);
  const Image image = render(scene, settings);
  EXPECT_EQ(image.encoding(), PixelEncoding::srgb);
  EXPECT_FLOAT_EQ(image.at(0, 0, 3), 0.0f);
  EXPECT_FLOAT_EQ(image.at(32, 32, 3), 1.0f);
}

TEST(Renderer, DepthMatchesAnalyticSphere) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 50, 5), SurfaceMaterial::clay());
  const Camera camera = Camera::look_at(Vec3(0, -400, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  const Image depth = Renderer(scene).depth(camera, 33, 33);
  EXPECT_NEAR(depth.at(16, 16), 350.0, 0.2);
  EXPECT_TRUE(std::isinf(depth.at(0, 0)));
}
