#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "spatial/winding_number.hpp"

using namespace forensim;

namespace {

std::vector<Vec3> random_points(int count, double spread, std::uint64_t seed) {
  RandomStream rng(seed, 0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    points.emplace_back(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
  }
  return points;
}

/// Fast evaluation within `tolerance` of the exact sum at every point; returns the largest error.
double expect_fast_equals_exact(const TriMesh& mesh, const std::vector<Vec3>& points, double tolerance,
                                double beta = 2.5) {
  const WindingNumber fast(mesh, beta);
  const std::vector<double> batch = fast.evaluate_batch(points);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double exact = winding_number_exact(mesh, points[i]);
    const double value = fast.evaluate(points[i]);
    worst = std::max(worst, std::abs(value - exact));
    EXPECT_NEAR(value, exact, tolerance) << "point " << i;
    EXPECT_EQ(batch[i], value);
  }
  return worst;
}

}  // namespace

TEST(WindingNumber, SolidAngleOfOctantIsOneEighth) {
  // The triangle (1,0,0), (0,1,0), (0,0,1) seen from the origin covers 1/8 of the sphere; the origin is on
  // its back side, so the angle is positive.
  EXPECT_NEAR(triangle_solid_angle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)),
              4.0 * 3.14159265358979323846 / 8.0, 1e-12);
}

TEST(WindingNumber, ExactIsOneInsideZeroOutsideClosedMeshes) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 2);
  EXPECT_NEAR(winding_number_exact(sphere, Vec3(0.1, 0.2, 0.3)), 1.0, 1e-12);
  EXPECT_NEAR(winding_number_exact(sphere, Vec3(1.5, 0.2, 0.3)), 0.0, 1e-12);
  const TriMesh box = make_box_mesh(Vec3::Zero(), Vec3(1, 2, 3), 2);
  EXPECT_NEAR(winding_number_exact(box, Vec3(0.99, 1.99, 0.01)), 1.0, 1e-10);
  EXPECT_NEAR(winding_number_exact(box, Vec3(1.01, 1.0, 1.0)), 0.0, 1e-10);
}

TEST(WindingNumber, FastEqualsExactOnIcosphere) {
  const TriMesh sphere = make_icosphere(Vec3(0.1, -0.1, 0.2), 1.0, 4);
  const std::vector<Vec3> points = random_points(300, 2.0, 41);
  const double coarse = expect_fast_equals_exact(sphere, points, 3e-3);
  // A larger opening distance converges to the exact value (third-order far field).
  const double fine = expect_fast_equals_exact(sphere, points, 5e-4, 4.0);
  EXPECT_LT(fine, coarse / 4.0);
}

TEST(WindingNumber, FastEqualsExactOnBoxAndOpenSphere) {
  expect_fast_equals_exact(make_box_mesh(Vec3(-1, -1, -0.5), Vec3(1, 0.7, 0.5), 8), random_points(400, 1.6, 42), 3e-3);
  TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 4);
  std::vector<bool> keep(sphere.triangle_count(), true);
  for (int f = 0; f < 30; ++f) keep[f] = false;
  expect_fast_equals_exact(extract_triangles(sphere, keep), random_points(400, 1.6, 43), 3e-3);
}

TEST(WindingNumber, ClassifiesInsideOutsideOfClosedAndHoledSpheres) {
  const TriMesh closed = make_icosphere(Vec3::Zero(), 1.0, 4);
  TriMesh holed = closed;
  {
    std::vector<bool> keep(closed.triangle_count(), true);
    for (int f = 0; f < 12; ++f) keep[f] = false;  // a small hole
    holed = extract_triangles(closed, keep);
  }
  ASSERT_FALSE(check_topology(holed).is_closed());
  const WindingNumber w_closed(closed);
  const WindingNumber w_holed(holed);
  const std::vector<Vec3> points = random_points(3000, 1.5, 44);
  const std::vector<bool> inside = w_holed.inside_batch(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = points[i].norm();
    if (r < 0.98) {
      EXPECT_NEAR(w_closed.evaluate(points[i]), 1.0, 3e-3);
    } else if (r > 1.02) {
      EXPECT_NEAR(w_closed.evaluate(points[i]), 0.0, 3e-3);
    }
    // The hole spans ~0.03 of the sphere's area: classification is still right away from the surface.
    if (r < 0.9) {
      EXPECT_TRUE(inside[i]) << "point " << i;
    }
    if (r > 1.1) {
      EXPECT_FALSE(inside[i]) << "point " << i;
    }
  }
}

TEST(WindingNumber, EmptyMeshAndBadBeta) {
  EXPECT_EQ(WindingNumber(TriMesh{}).evaluate(Vec3::Zero()), 0.0);
  EXPECT_THROW(WindingNumber(make_icosphere(Vec3::Zero(), 1.0, 0), 0.5), InputError);
}

TEST(WindingNumber, SameTreeAndValuesAtAnyThreadCount) {
  // 20k triangles: the tree's halves above 4096 triangles are built concurrently.
  const TriMesh mesh = make_icosphere(Vec3(1, 2, 3), 50.0, 5);
  std::vector<Vec3> points;
  for (int i = 0; i < 200; ++i)
    points.push_back(Vec3(1, 2, 3) + Vec3(std::sin(i), std::cos(1.3 * i), std::sin(0.7 * i)) * 0.6 * i);
  set_thread_count(1);
  const WindingNumber one(mesh);
  const std::vector<double> a = one.evaluate_batch(points);
  set_thread_count(0);
  const WindingNumber all(mesh);
  const std::vector<double> b = all.evaluate_batch(points);
  EXPECT_EQ(one.node_count(), all.node_count());
  EXPECT_EQ(a, b);
  for (std::size_t i = 0; i < points.size(); i += 17) EXPECT_NEAR(a[i], winding_number_exact(mesh, points[i]), 5e-3);
}
