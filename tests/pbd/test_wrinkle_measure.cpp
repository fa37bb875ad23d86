#include "pbd/wrinkle_measure.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "geometry/primitives.hpp"
#include "pbd_test_models.hpp"

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

namespace {

/// The sheet lifted by amplitude cos(2 pi x / wavelength) along +z.
std::vector<Vec3> waved(const TriMesh& sheet, double amplitude, double wavelength) {
  std::vector<Vec3> out = sheet.positions;
  for (Vec3& p : out) p.z() += amplitude * std::cos(6.283185307179586 * p.x() / wavelength);
  return out;
}

/// Vertices of the (nx + 1) x (ny + 1) sheet at least `margin` cells from its border.
std::vector<std::uint8_t> interior(int nx, int ny, int margin) {
  std::vector<std::uint8_t> mask;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mask.push_back(i >= margin && i <= nx - margin && j >= margin && j <= ny - margin ? 1 : 0);
  return mask;
}

}  // namespace

TEST(WrinkleSize, HeightAndWavelengthOfASinusoidalWrinkle) {
  // 60 mm x 30 mm, 0.5 mm cells (wavelengths of 4 to 20 cells); measured away from the border, where a plane wave is an
  // eigenvector of the uniform Laplacian (eigenvalue k = 2/3 (1 - cos theta) on this grid, theta the phase step per
  // cell), so the fine part left by the Taubin steps is the wave times 1 - ((1 - 0.5 k) (1 + 0.53 k))^10.
  const TriMesh sheet = test::make_grid_sheet(120, 60, 0.5);
  const std::vector<std::uint8_t> mask = interior(120, 60, 25);
  const double amplitude = 0.3;
  for (double wavelength : {2.0, 5.0, 10.0}) {
    const std::vector<Vec3> x = waved(sheet, amplitude, wavelength);
    const WrinkleSize w = wrinkle_size(x, sheet.positions, sheet.triangles, 10, mask);
    const double k = 2.0 / 3.0 * (1.0 - std::cos(6.283185307179586 * 0.5 / wavelength));
    const double kept = std::abs(1.0 - std::pow((1.0 - 0.5 * k) * (1.0 + 0.53 * k), 10));  // < 0: amplified
    EXPECT_NEAR(w.height_mm, kept * amplitude / std::sqrt(2.0), 0.03 * kept * amplitude) << wavelength;
    // The wavelength of the piecewise-linear surface: four cells per wavelength read about 10 % short.
    EXPECT_NEAR(w.wavelength_mm, wavelength, (wavelength < 3.0 ? 0.12 : 0.03) * wavelength);
    // Twice the amplitude: twice the height, the same wavelength.
    const WrinkleSize twice =
        wrinkle_size(waved(sheet, 2.0 * amplitude, wavelength), sheet.positions, sheet.triangles, 10, mask);
    EXPECT_NEAR(twice.height_mm, 2.0 * w.height_mm, 1e-9);
    EXPECT_NEAR(twice.wavelength_mm, w.wavelength_mm, 1e-9);
  }
  // A flat skin has no wrinkles; one slid along the surface neither.
  std::vector<Vec3> slid = sheet.positions;
  for (Vec3& p : slid) p.x() += 0.2;
  const WrinkleSize none = wrinkle_size(slid, sheet.positions, sheet.triangles);
  EXPECT_EQ(none.height_mm, 0.0);
  EXPECT_EQ(none.wavelength_mm, 0.0);
}

TEST(WrinkleSize, SmoothingKeepsFoldsAndDropsTheLiftOfAWholeRegion) {
  const TriMesh sheet = test::make_grid_sheet(120, 60, 0.5);
  const std::vector<std::uint8_t> mask = interior(120, 60, 25);
  // Folds two cells apart count almost fully; a lift 60 cells long is the shape of the body, not a wrinkle.
  const WrinkleSize fold = wrinkle_size(waved(sheet, 0.3, 1.0), sheet.positions, sheet.triangles, 10, mask);
  const WrinkleSize lift = wrinkle_size(waved(sheet, 0.3, 30.0), sheet.positions, sheet.triangles, 10, mask);
  EXPECT_GT(fold.height_mm, 0.95 * 0.3);  // the alternating fold's RMS is its amplitude
  EXPECT_LT(lift.height_mm, 0.01 * fold.height_mm);
  EXPECT_THROW(wrinkle_size(sheet.positions, {Vec3::Zero()}, sheet.triangles), InputError);
  EXPECT_THROW(wrinkle_size(sheet.positions, sheet.positions, {Tri{0, 1, 100000}}), InputError);
}

TEST(WrinkleSize, LiftOffFollowsTheWaveWithItsSign) {
  // On the sheet with the normal +z, the per-vertex lift-off of a 2 mm wave (kept almost whole by the smoothing) is
  // the wave itself: positive on its crests, negative in its troughs, its RMS the wrinkle height.
  const TriMesh sheet = test::make_grid_sheet(120, 60, 0.5);
  const std::vector<std::uint8_t> mask = interior(120, 60, 25);
  const double amplitude = 0.3, wavelength = 2.0;
  const std::vector<Vec3> x = waved(sheet, amplitude, wavelength);
  const std::vector<double> h = wrinkle_lift_off_mm(x, sheet.positions, sheet.triangles);
  ASSERT_EQ(h.size(), x.size());
  double sum = 0.0, count = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (mask[i] == 0) continue;
    const double wave = x[i].z() - sheet.positions[i].z();
    if (std::abs(wave) > 0.5 * amplitude) {
      EXPECT_GT(h[i] * wave, 0.0) << i;
    }
    sum += h[i] * h[i];
    ++count;
  }
  EXPECT_NEAR(std::sqrt(sum / count), wrinkle_size(x, sheet.positions, sheet.triangles, 10, mask).height_mm, 1e-9);
  EXPECT_THROW(wrinkle_lift_off_mm(x, std::vector<Vec3>(3), sheet.triangles), InputError);
}
