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

  // A cut plane of the outer object alone opens it (hollow, no cap) and shows the whole inner sphere.
  scene.cutaway.reset();
  scene.objects[0].cutaway = CutPlane{Vec3::Zero(), Vec3(0, -1, 0)};
  const int inner_whole = count_green(render(scene, settings));
  EXPECT_GT(inner_whole, 300);
  // The scene's plane, with the inner object exempt, gives the same picture.
  scene.objects[0].cutaway.reset();
  scene.cutaway = CutPlane{Vec3::Zero(), Vec3(0, -1, 0)};
  scene.objects[1].use_scene_cutaway = false;
  scene.objects[0].material.draw_cap = false;
  EXPECT_EQ(count_green(render(scene, settings)), inner_whole);
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

namespace {

// A large square facing -Y (towards a camera on the -Y side) at y = 0.
TriMesh wall(double half) {
  TriMesh quad;
  quad.positions = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.triangle_uvs = quad.triangles;
  quad.normals.assign(4, Vec3(0, -1, 0));
  return quad;
}

float centre_linear(const Scene& scene, int channel = 0) {
  RenderSettings settings = small_settings(9, 64);
  return Renderer(scene).render_linear(scene.camera, settings).at(4, 4, channel);
}

}  // namespace

TEST(Renderer, DirectionalLightOfIntensityOneShowsTheAlbedo) {
  Scene scene = plain_scene();
  scene.add(wall(100), matte(Vec3f(0.5f, 0.5f, 0.5f)));
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  scene.lights.push_back(Light::directional(Vec3(0, -1, 0), 1.0, 0.0));
  EXPECT_NEAR(centre_linear(scene), 0.5f, 1e-3f);
  // At 60 degrees incidence: cos = 0.5.
  scene.lights[0].direction = Vec3(0, -0.5, std::sqrt(0.75));
  EXPECT_NEAR(centre_linear(scene), 0.25f, 1e-3f);
}

TEST(Renderer, WireframeDarkensOnlyNearTriangleEdges) {
  Scene scene = plain_scene();
  SurfaceMaterial m = matte(Vec3f(0.5f, 0.5f, 0.5f));
  m.wire_width_mm = 1.0;
  m.wire_colour = Vec3f(0.1f, 0.1f, 0.1f);
  scene.add(wall(100), m);  // its diagonal edge runs through the centre
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  scene.lights.push_back(Light::directional(Vec3(0, -1, 0), 1.0, 0.0));
  RenderSettings settings = small_settings(9, 64);
  const Image image = Renderer(scene).render_linear(scene.camera, settings);
  // 20 mm view over 9 pixels: the centre pixel (2.2 mm wide) straddles the edge; the corner pixel lies
  // 9.4 mm from the diagonal.
  EXPECT_LT(image.at(4, 4, 0), 0.35f);
  EXPECT_NEAR(image.at(7, 7, 0), 0.5f, 1e-3f);
  m.wire_width_mm = 0.0;
  scene.objects[0].material = m;
  EXPECT_NEAR(centre_linear(scene), 0.5f, 1e-3f);
}

TEST(Renderer, SphereLightFollowsTheInverseSquareLaw) {
  // A sphere of radiance L and radius r at distance d gives irradiance pi L r^2 / d^2 (normal incidence),
  // so a Lambertian surface of albedo a shows radiance a L r^2 / d^2.
  Scene scene = plain_scene();
  scene.add(wall(400), matte(Vec3f(0.5f, 0.5f, 0.5f)));
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 2);
  scene.lights.push_back(Light::sphere(Vec3(0, -50, 0), 5.0, 100.0));
  EXPECT_NEAR(centre_linear(scene), 0.5f * 100.0f * 25.0f / 2500.0f, 0.01f);
  scene.lights[0].position = Vec3(0, -100, 0);
  EXPECT_NEAR(centre_linear(scene), 0.5f * 100.0f * 25.0f / 10000.0f, 0.003f);
}

TEST(Renderer, RectangleLightMatchesSmallSourceLimit) {
  // A small square (side s) at distance d facing the surface: E ~ L s^2 / d^2.
  Scene scene = plain_scene();
  scene.add(wall(400), matte(Vec3f(1.0f, 1.0f, 1.0f)));
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 2);
  scene.lights.push_back(Light::rectangle(Vec3(-2, -100, -2), Vec3(0, 0, 4), Vec3(4, 0, 0), 1000.0));
  const float expected = static_cast<float>(1000.0 * 16.0 / 10000.0 / M_PI);
  EXPECT_NEAR(centre_linear(scene), expected, 0.01f * expected);
  // Emitting away from the surface: dark.
  std::swap(scene.lights[0].edge_u, scene.lights[0].edge_v);
  EXPECT_EQ(centre_linear(scene), 0.0f);
}

TEST(Renderer, NormalMapTiltsTheShading) {
  Scene scene = plain_scene();
  scene.add(wall(100), matte(Vec3f(0.5f, 0.5f, 0.5f)));
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 20);
  scene.lights.push_back(Light::directional(Vec3(0, -1, 0), 1.0, 0.0));
  const float flat = centre_linear(scene);
  // Tangent-space normal tilted 60 degrees along +u: n = (sin 60, 0, cos 60), stored as (n + 1) / 2.
  auto map = std::make_shared<Image>(4, 4, 3, 0.5f, PixelEncoding::data);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) map->set_rgba(x, y, Vec4f(0.5f + 0.5f * 0.8660254f, 0.5f, 0.75f, 1.0f));
  scene.objects[0].material.normal_map = map;
  EXPECT_NEAR(centre_linear(scene), 0.5f * flat, 2e-3f);
}

TEST(Renderer, SkinTerminatorIsRedderThanAPlainSurface) {
  const auto terminator_ratio = [](const SurfaceMaterial& material) {
    Scene scene = plain_scene();
    scene.add(make_icosphere(Vec3::Zero(), 50, 4), material);
    scene.camera = Camera::orthographic(Vec3(0, -400, 0), Vec3::Zero(), Vec3::UnitZ(), 110);
    scene.lights.push_back(Light::directional(Vec3(-1, 0, 0), 1.0, 0.0));
    RenderSettings settings = small_settings(64, 4);
    const Image image = Renderer(scene).render_linear(scene.camera, settings);
    // Pixels just past the terminator (the sphere's centre column and a little right of it).
    double red = 0, green = 0;
    for (int y = 20; y < 44; ++y)
      for (int x = 32; x < 38; ++x) {
        red += image.at(x, y, 0);
        green += image.at(x, y, 1);
      }
    return red / std::max(green, 1e-9);
  };
  SurfaceMaterial skin = SurfaceMaterial::skin(Vec3f(0.5f, 0.5f, 0.5f));
  skin.specular = 0;
  EXPECT_GT(terminator_ratio(skin), 1.3);
}

TEST(Renderer, ObjectTransformMovesTheObject) {
  Scene scene = plain_scene();
  scene.lights.push_back(Light::directional(Vec3(0, -1, 0), 1.0, 0.0));
  scene.add(make_icosphere(Vec3::Zero(), 10, 2), matte(Vec3f(0.8f, 0.8f, 0.8f)));
  scene.camera = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 100);
  scene.objects[0].transform = Eigen::Translation3d(30, 0, 0) * Eigen::Scaling(1.5);
  const Image image = render(scene, small_settings(50, 1));
  // The sphere (radius 15 after scaling) is centred at x = 30 mm, i.e. pixel 40 of 50.
  EXPECT_GT(image.at(40, 25, 0), 0.3f);
  EXPECT_GT(image.at(40 - 6, 25, 0), 0.3f);
  EXPECT_LT(image.at(25, 25, 0), 0.01f);
  EXPECT_LT(image.at(40 - 9, 25, 0), 0.01f);
}

TEST(Renderer, EmptySceneShowsTheBackground) {
  Scene scene;
  RenderSettings settings = small_settings(8, 1);
  settings.background = Vec4f(0.2f, 0.4f, 0.6f, 1.0f);
  const Image image = render(scene, settings);
  EXPECT_EQ(image.rgba(3, 3), settings.background);
  scene.add(TriMesh{}, SurfaceMaterial::clay(), "nothing");
  EXPECT_EQ(render(scene, settings).rgba(3, 3), settings.background);
}
