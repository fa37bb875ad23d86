#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

#include "core/random.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/obj_reader.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "spatial/winding_number.hpp"
#include "support/test_support.hpp"

using namespace forensim;

/// On the 100k-triangle skull: closest points and winding numbers equal brute force on random points in
/// its bounding box, and a ray from each inside point along +y hits the skull exactly as brute force says.
TEST(RealScans, SkullQueriesEqualBruteForce) {
  FORENSIM_REQUIRE_DATA(path, "skull-mesh/skull.obj");
  const TriMesh skull = test::read_obj_positions(path.string());
  auto start = std::chrono::steady_clock::now();
  const RayCaster caster(skull);
  const ClosestPointQuery closest(skull);
  const WindingNumber winding(skull);
  std::cout << "built ray caster, closest point query and winding number tree for " << skull.triangle_count()
            << " triangles in " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
  const BoundingBox box = bounding_box(skull.positions);
  RandomStream rng(51, 0);
  int inside = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 p(rng.uniform(box.min.x(), box.max.x()), rng.uniform(box.min.y(), box.max.y()),
                 rng.uniform(box.min.z(), box.max.z()));
    double best = std::numeric_limits<double>::infinity();
    double t_best = std::numeric_limits<double>::infinity();
    for (const Tri& t : skull.triangles) {
      const Vec3& a = skull.positions[t[0]];
      const Vec3& b = skull.positions[t[1]];
      const Vec3& c = skull.positions[t[2]];
      const Vec3 bary = closest_point_on_triangle(p, a, b, c);
      best = std::min(best, (bary[0] * a + bary[1] * b + bary[2] * c - p).norm());
      double tt = 0.0;
      Vec3 bb;
      if (ray_triangle_intersect(p, Vec3(0, 1, 0), a, b, c, 0.0, t_best, tt, bb)) t_best = std::min(t_best, tt);
    }
    const auto got = closest.query(p);
    ASSERT_TRUE(got);
    EXPECT_NEAR(got->distance, best, 1e-12 * (1 + best));
    const auto hit = caster.intersect(p, Vec3(0, 1, 0));
    ASSERT_EQ(hit.has_value(), std::isfinite(t_best));
    if (hit) {
      EXPECT_NEAR(hit->t, t_best, 1e-9);
    }
    const double exact = winding_number_exact(skull, p);
    EXPECT_NEAR(winding.evaluate(p), exact, 5e-3);
    if (exact > 0.5) ++inside;
  }
  std::cout << inside << " of 300 random points in the bounding box are inside the skull\n";
  EXPECT_GT(inside, 0);
}
