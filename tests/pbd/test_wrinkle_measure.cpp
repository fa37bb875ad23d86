#include "pbd/wrinkle_measure.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

TEST(WrinkleMeasure, SphereHasCurvatureOneOverRadiusAndLittleRoughness) {
  const double r = 20.0;
  const TriMesh sphere = make_icosphere(Vec3::Zero(), r, 4);
  const WrinkleMeasure m = wrinkle_measure(sphere.positions, sphere.triangles);
  EXPECT_NEAR(m.mean_abs_curvature_per_mm, 1.0 / r, 0.03 / r);
  // Taubin smoothing barely moves a smooth sphere.
  EXPECT_LT(m.rms_smooth_distance_mm, 0.005 * r);
}

TEST(WrinkleMeasure, GrowsWithFoldsAndScalesWithSize) {
  const double r = 20.0;
  const TriMesh sphere = make_icosphere(Vec3::Zero(), r, 4);
  const WrinkleMeasure smooth = wrinkle_measure(sphere.positions, sphere.triangles);
  std::vector<Vec3> wrinkled = sphere.positions, stronger = sphere.positions;
  for (std::size_t i = 0; i < wrinkled.size(); ++i) {
    const Vec3 n = sphere.positions[i].normalized();
    const double wave = std::sin(12.0 * std::atan2(n.y(), n.x())) * std::sin(10.0 * std::acos(n.z()));
    wrinkled[i] += 0.2 * wave * n;
    stronger[i] += 0.6 * wave * n;
  }
  const WrinkleMeasure a = wrinkle_measure(wrinkled, sphere.triangles);
  const WrinkleMeasure b = wrinkle_measure(stronger, sphere.triangles);
  EXPECT_GT(a.rms_smooth_distance_mm, smooth.rms_smooth_distance_mm);
  EXPECT_GT(b.rms_smooth_distance_mm, 1.5 * a.rms_smooth_distance_mm);
  EXPECT_GT(a.mean_abs_curvature_per_mm, smooth.mean_abs_curvature_per_mm);
  EXPECT_GT(b.mean_abs_curvature_per_mm, a.mean_abs_curvature_per_mm);
  // Twice the size: twice the distances, half the curvature.
  std::vector<Vec3> twice = stronger;
  for (Vec3& p : twice) p *= 2.0;
  const WrinkleMeasure c = wrinkle_measure(twice, sphere.triangles);
  EXPECT_NEAR(c.rms_smooth_distance_mm, 2.0 * b.rms_smooth_distance_mm, 1e-9);
  EXPECT_NEAR(c.mean_abs_curvature_per_mm, 0.5 * b.mean_abs_curvature_per_mm, 1e-12);
}

TEST(WrinkleMeasure, MaskSelectsAPart) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 10.0, 3);
  std::vector<Vec3> p = sphere.positions;
  std::vector<std::uint8_t> top(p.size(), 0), bottom(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    top[i] = p[i].z() > 0.0;
    bottom[i] = p[i].z() < 0.0;
    // Fold only the top half.
    if (p[i].z() > 0.0) p[i] *= 1.0 + 0.05 * std::sin(5.0 * p[i].x());
  }
  const WrinkleMeasure t = wrinkle_measure(p, sphere.triangles, 10, top);
  const WrinkleMeasure b = wrinkle_measure(p, sphere.triangles, 10, bottom);
  EXPECT_GT(t.mean_abs_curvature_per_mm, 1.5 * b.mean_abs_curvature_per_mm);
  EXPECT_THROW(wrinkle_measure(p, sphere.triangles, 10, std::vector<std::uint8_t>(3, 1)), InputError);
}
