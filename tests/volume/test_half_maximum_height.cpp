#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "volume/half_maximum_height.hpp"
#include "volume/iso_surface.hpp"

namespace forensim {
namespace {

constexpr double k_soft = 1000.0, k_bone = 1800.0, k_sigma = 1.5;

/// A CT-like ball of bone in soft tissue on 3.2 x 3.2 x 1.5 mm voxels (headsq's), its edge blurred by a Gaussian
/// point-spread function of `sigma` mm: the value at radius r is b + (c - b) erfc((r - R) / (sqrt 2 sigma)) / 2
/// (the 1-D blur of a step, exact where the radius is large beside sigma).
ScalarGrid blurred_ball(double radius, double sigma = k_sigma) {
  const Vec3 spacing(3.2, 3.2, 1.5);
  const int nx = 41, ny = 41, nz = 87;
  ScalarGrid grid = ScalarGrid::filled(nx, ny, nz, 0.0f);
  grid.spacing = spacing;
  grid.origin = -0.5 * Vec3((nx - 1) * spacing.x(), (ny - 1) * spacing.y(), (nz - 1) * spacing.z());
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double r = grid.index_to_world(Vec3(i, j, k)).norm();
        const double value = k_soft + (k_bone - k_soft) * 0.5 * std::erfc((r - radius) / (std::sqrt(2.0) * sigma));
        grid.at(i, j, k) = float(value);
      }
    }
  }
  return grid;
}

double mean_radius(const TriMesh& mesh) {
  double sum = 0.0;
  for (const Vec3& p : mesh.positions) sum += p.norm();
  return sum / double(mesh.positions.size());
}

/// A shell from `inner` to `outer` mm, the difference of two blurred balls over soft tissue.
ScalarGrid blurred_shell(double outer, double inner) {
  ScalarGrid ct = blurred_ball(outer);
  const ScalarGrid hole = blurred_ball(inner);
  for (std::size_t v = 0; v < ct.values.size(); ++v) ct.values[v] = float(ct.values[v] - hole.values[v] + k_soft);
  return ct;
}

double mean_outer_radius(const TriMesh& mesh) {
  double split = 0.0;
  for (const Vec3& p : mesh.positions) split += p.norm() / double(mesh.positions.size());
  double sum = 0.0, count = 0.0;
  for (const Vec3& p : mesh.positions) {
    if (p.norm() < split) continue;
    sum += p.norm();
    count += 1.0;
  }
  return sum / count;
}

TEST(HalfMaximumHeight, ThresholdOfABlurredBallIsHalfWayAndPutsTheSurfaceOnTheEdge) {
  const double radius = 40.0;
  const ScalarGrid ct = blurred_ball(radius);
  HalfMaximumOptions options;
  options.iso_value = 1150.0;
  const TriMesh seed = extract_iso_surface(ct, options.iso_value);
  // 1150 lies where erfc(x) / 2 = 150 / 800: x = 0.63, i.e. 1.3 mm outside the edge.
  EXPECT_GT(mean_radius(seed) - radius, 1.0);
  const HalfMaximumHeight hmh = half_maximum_height(measure_edge_profiles(seed, ct, options));
  EXPECT_EQ(hmh.profiles, seed.positions.size());
  EXPECT_GT(hmh.used, seed.positions.size() / 2);
  EXPECT_NEAR(hmh.peak, k_bone, 5.0);
  EXPECT_NEAR(hmh.background, k_soft, 10.0);  // the blur's tail one 1.5 mm slice out
  EXPECT_NEAR(hmh.level, 0.5 * (k_soft + k_bone), 5.0);
  const TriMesh at_level = extract_iso_surface(ct, hmh.level);
  EXPECT_NEAR(mean_radius(at_level), radius, 0.15);
}

TEST(HalfMaximumHeight, StructuresThinnerThanTheBlurAreNotPlateaus) {
  // A shell 1 mm thick under a 1.5 mm blur never reaches the bone value: no plateau profile, no threshold.
  const double outer = 40.0, inner = 39.0;
  const ScalarGrid ct = blurred_shell(outer, inner);
  HalfMaximumOptions options;
  options.iso_value = 1150.0;
  const TriMesh seed = extract_iso_surface(ct, options.iso_value);
  ASSERT_FALSE(seed.triangles.empty());
  const HalfMaximumHeight plateaus = half_maximum_height(measure_edge_profiles(seed, ct, options));
  EXPECT_GT(plateaus.profiles, 0u);
  EXPECT_EQ(plateaus.used, 0u);
  const HalfMaximumHeight all = half_maximum_height(measure_edge_profiles(seed, ct, options), false);
  EXPECT_EQ(all.used, all.profiles);
  EXPECT_LT(all.peak, k_soft + 0.5 * (k_bone - k_soft));  // erf(1 / (2 sqrt 2 * 1.5)) of the contrast
}

TEST(HalfMaximumHeight, ProfileFindsTheAnalyticCrossings) {
  const double radius = 40.0;
  const ScalarGrid ct = blurred_ball(radius);
  HalfMaximumOptions options;
  options.iso_value = 1150.0;
  // Along x (3.2 mm voxels) from a point 1 mm inside the edge.
  const EdgeProfile p = measure_edge_profile(ct, Vec3(radius - 1.0, 0, 0), Vec3::UnitX(), options);
  ASSERT_TRUE(p.found);
  EXPECT_DOUBLE_EQ(p.extent_mm, 3.2);
  const double x_iso = std::sqrt(2.0) * k_sigma * 0.6322;  // erfc(x) = 0.375
  EXPECT_NEAR(p.crossing_mm, 1.0 + x_iso, 0.25);           // trilinear between 3.2 mm samples
  EXPECT_NEAR(p.crossing_of(1400.0), 1.0, 0.25);
  EXPECT_NEAR(p.crossing_of(1150.0), p.crossing_mm, 1e-9);
  EXPECT_TRUE(std::isnan(p.crossing_of(2000.0)));  // above the peak
  // Along z (1.5 mm slices) the extent is the slice spacing.
  const EdgeProfile z = measure_edge_profile(ct, Vec3(0, 0, radius), Vec3::UnitZ(), options);
  ASSERT_TRUE(z.found);
  EXPECT_DOUBLE_EQ(z.extent_mm, 1.5);
  EXPECT_NEAR(z.crossing_of(1400.0), 0.0, 0.15);
  // A point far from any crossing has no profile.
  EXPECT_FALSE(measure_edge_profile(ct, Vec3::Zero(), Vec3::UnitX(), options).found);
}

TEST(HalfMaximumHeight, ThinPlateLevelIsTheBlurredPlatesValueAtItsSurface) {
  // A plate of thickness d over background b, blurred by a Gaussian of s: its profile, computed here from erf
  // directly, at the plate's surface (x = 0) and at its centre (the peak).
  const double b = k_soft, c = k_bone;
  for (const double s : {0.8, 1.5}) {
    for (const double d : {0.5, 1.0, 2.0, 4.0}) {
      const auto profile = [&](double x) {
        return b + 0.5 * (c - b) * (std::erf(x / (std::sqrt(2.0) * s)) - std::erf((x - d) / (std::sqrt(2.0) * s)));
      };
      const double peak = profile(0.5 * d);
      EXPECT_NEAR(thin_plate_level(peak, b, c), profile(0.0), 1e-6) << "d " << d << " s " << s;
      // Above the plate's own half-maximum, which lies outside it.
      EXPECT_GT(thin_plate_level(peak, b, c), 0.5 * (peak + b));
    }
  }
  // Thick (peak at the plateau) or no plateau given: the half-maximum.
  EXPECT_DOUBLE_EQ(thin_plate_level(1800.0, 1000.0, 1800.0), 1400.0);
  EXPECT_DOUBLE_EQ(thin_plate_level(1300.0, 1000.0, 0.0), 1150.0);
}

TEST(HalfMaximumHeight, MovesPutThickAndThinStructuresOnTheirEdges) {
  HalfMaximumOptions options;
  options.iso_value = 1150.0;
  const double level = 0.5 * (k_soft + k_bone);
  // Thick: the ball's surface moves to the threshold, on the edge.
  const ScalarGrid ball = blurred_ball(40.0);
  TriMesh surface = extract_iso_surface(ball, options.iso_value);
  const HalfMaximumMoves thick =
      move_to_half_maximum(surface, measure_edge_profiles(surface, ball, options), level, k_bone);
  EXPECT_EQ(thick.to_level, surface.positions.size());
  EXPECT_LT(thick.mean_shift_mm, -1.0);
  EXPECT_NEAR(mean_radius(surface), 40.0, 0.15);
  // Thin: a 1.5 mm shell under the 1.5 mm blur peaks at about 1306, below the threshold; an iso-surface at the
  // threshold loses it, the plate model puts its outer surface on its edge, its own half-maximum (about the 1150
  // seed) lies outside.
  const ScalarGrid shell = blurred_shell(40.0, 38.5);
  EXPECT_TRUE(extract_iso_surface(shell, level).triangles.empty());
  const TriMesh seed = extract_iso_surface(shell, options.iso_value);
  TriMesh plate = seed, own = seed;
  const std::vector<EdgeProfile> profiles = measure_edge_profiles(seed, shell, options);
  const HalfMaximumMoves thin = move_to_half_maximum(plate, profiles, level, k_bone);
  move_to_half_maximum(own, profiles, level, 0.0);
  EXPECT_GT(thin.to_own, seed.positions.size() / 2);
  EXPECT_NEAR(mean_outer_radius(plate), 40.0, 0.25);
  EXPECT_GT(mean_outer_radius(own) - 40.0, 0.5);
  EXPECT_EQ(plate.triangles, seed.triangles);  // moved, not re-meshed
  EXPECT_THROW(move_to_half_maximum(plate, profiles, std::nan(""), k_bone), InputError);
}

TEST(HalfMaximumHeight, SameThresholdAtAnyThreadCount) {
  const ScalarGrid ct = blurred_ball(35.0);
  HalfMaximumOptions options;
  options.iso_value = 1150.0;
  const TriMesh seed = extract_iso_surface(ct, options.iso_value);
  set_thread_count(1);
  const HalfMaximumHeight one = half_maximum_height(measure_edge_profiles(seed, ct, options));
  set_thread_count(0);
  const HalfMaximumHeight all = half_maximum_height(measure_edge_profiles(seed, ct, options));
  EXPECT_EQ(one.used, all.used);
  EXPECT_EQ(one.level, all.level);
  EXPECT_EQ(one.level_sd, all.level_sd);
}

TEST(HalfMaximumHeight, BadOptionsAreInputErrors) {
  const ScalarGrid ct = blurred_ball(35.0);
  const TriMesh seed = extract_iso_surface(ct, 1150.0);
  HalfMaximumOptions options;
  options.iso_value = std::nan("");
  EXPECT_THROW(measure_edge_profiles(seed, ct, options), InputError);
  options.iso_value = 1150.0;
  options.step_voxels = 0.0;
  EXPECT_THROW(measure_edge_profiles(seed, ct, options), InputError);
  options.step_voxels = 0.1;
  options.background_voxels = -1.0;
  EXPECT_THROW(measure_edge_profiles(seed, ct, options), InputError);
  // An empty surface measures nothing.
  options.background_voxels = 1.5;
  const HalfMaximumHeight none = half_maximum_height(measure_edge_profiles(TriMesh{}, ct, options));
  EXPECT_EQ(none.used, 0u);
  EXPECT_EQ(none.level, 0.0);
}

}  // namespace
}  // namespace forensim
