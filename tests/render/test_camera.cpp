#include <gtest/gtest.h>

#include "core/error.hpp"
#include "render/camera.hpp"

using namespace forensim;

TEST(Camera, ProjectInvertsRay) {
  const Camera camera = Camera::look_at(Vec3(100, -300, 50), Vec3(0, 0, 10), Vec3::UnitZ(), 35);
  for (const Vec2& pixel : {Vec2(10.5, 20.25), Vec2(0, 0), Vec2(159, 99)}) {
    const Ray3 ray = camera.ray(pixel[0], pixel[1], 160, 100);
    Vec2 back;
    double depth;
    ASSERT_TRUE(camera.project(ray.origin + 123.0 * ray.direction, 160, 100, &back, &depth));
    EXPECT_NEAR((back - pixel).norm(), 0.0, 1e-9);
  }
  const Camera ortho = Camera::orthographic(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 80);
  const Ray3 ray = ortho.ray(30, 40, 64, 64);
  Vec2 back;
  double depth;
  ASSERT_TRUE(ortho.project(ray.origin + 50.0 * ray.direction, 64, 64, &back, &depth));
  EXPECT_NEAR((back - Vec2(30, 40)).norm(), 0.0, 1e-9);
  EXPECT_FALSE(camera.project(Vec3(200, -600, 90), 160, 100, &back, &depth));  // behind the camera
}

TEST(Camera, FramedViewsContainTheWholeBox) {
  BoundingBox box;
  box.extend(Vec3(-30, -10, -120));
  box.extend(Vec3(40, 25, 130));
  for (const std::string& name : view_names()) {
    for (bool ortho : {false, true}) {
      FramingOptions options;
      options.orthographic = ortho;
      const Camera camera = frame_view(box, view_from_name(name), 1.5, options);
      for (int i = 0; i < 8; ++i) {
        const Vec3 corner((i & 1) ? box.max[0] : box.min[0], (i & 2) ? box.max[1] : box.min[1],
                          (i & 4) ? box.max[2] : box.min[2]);
        Vec2 pixel;
        double depth;
        ASSERT_TRUE(camera.project(corner, 300, 200, &pixel, &depth)) << name;
        EXPECT_GE(pixel[0], -1e-6) << name;
        EXPECT_LE(pixel[0], 300 + 1e-6) << name;
        EXPECT_GE(pixel[1], -1e-6) << name;
        EXPECT_LE(pixel[1], 200 + 1e-6) << name;
      }
    }
  }
}

TEST(Camera, NamedViewsLookFromTheRightSide) {
  BoundingBox box;
  box.extend(Vec3(-1, -1, -1));
  box.extend(Vec3(1, 1, 1));
  // LPS: the front is -Y, the subject's left +X, up +Z.
  EXPECT_LT(frame_view(box, ViewName::front, 1.0).eye()[1], -1.0);
  EXPECT_GT(frame_view(box, ViewName::back, 1.0).eye()[1], 1.0);
  EXPECT_GT(frame_view(box, ViewName::left, 1.0).eye()[0], 1.0);
  EXPECT_LT(frame_view(box, ViewName::right, 1.0).eye()[0], -1.0);
  EXPECT_GT(frame_view(box, ViewName::top, 1.0).eye()[2], 1.0);
  const Camera front = frame_view(box, ViewName::front, 1.0);
  EXPECT_GT(front.up()[2], 0.99);
  EXPECT_THROW(view_from_name("sideways"), InputError);
  EXPECT_THROW(Camera::look_at(Vec3::Zero(), Vec3::Zero(), Vec3::UnitZ()), InputError);
  EXPECT_THROW(Camera::look_at(Vec3(0, 0, -1), Vec3::Zero(), Vec3::UnitZ()), InputError);
}
