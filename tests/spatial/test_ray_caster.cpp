#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "spatial/ray_caster.hpp"

using namespace forensim;

namespace {

Vec3 random_unit(RandomStream& rng) {
  const double z = rng.uniform(-1.0, 1.0);
  const double phi = rng.uniform(0.0, 2.0 * 3.14159265358979323846);
  const double s = std::sqrt(1.0 - z * z);
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

struct BruteHit {
  Index triangle = -1;
  double t = std::numeric_limits<double>::infinity();
  Vec3 barycentric = Vec3::Zero();
};

BruteHit brute_force(const TriMesh& mesh, const Vec3& o, const Vec3& d) {
  BruteHit best;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    double tt = 0.0;
    Vec3 bary;
    if (ray_triangle_intersect(o, d, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], 0.0, best.t, tt,
                               bary) &&
        tt < best.t) {
      best.triangle = static_cast<Index>(f);
      best.t = tt;
      best.barycentric = bary;
    }
  }
  return best;
}

TriMesh sphere_with_hole() {
  TriMesh sphere = make_icosphere(Vec3(0.3, -0.2, 0.1), 1.5, 3);
  std::vector<bool> keep(sphere.triangle_count(), true);
  keep[5] = keep[6] = keep[7] = false;
  return extract_triangles(sphere, keep);
}

/// Casts `count` random rays (origins in a box around the mesh, uniform directions) and compares with brute
/// force. Hits may disagree only for rays grazing an edge of an open boundary.
void expect_equal_to_brute_force(const TriMesh& mesh, int count, std::uint64_t seed) {
  const RayCaster caster(mesh);
  RandomStream rng(seed, 0);
  int hits = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3 o(rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5));
    const Vec3 d = random_unit(rng) * rng.uniform(0.5, 2.0);
    const std::optional<RayHit> hit = caster.intersect(o, d);
    const BruteHit ref = brute_force(mesh, o, d);
    ASSERT_EQ(hit.has_value(), ref.triangle >= 0) << "ray " << i;
    if (!hit) continue;
    ++hits;
    EXPECT_NEAR(hit->t, ref.t, 1e-9 * (1.0 + ref.t)) << "ray " << i;
    const Vec3 on_ray = o + hit->t * d;
    EXPECT_LT((hit->point - on_ray).norm(), 1e-9) << "ray " << i;
    const Tri& tri = mesh.triangles[hit->triangle];
    const Vec3 from_bary = hit->barycentric[0] * mesh.positions[tri[0]] + hit->barycentric[1] * mesh.positions[tri[1]] +
                           hit->barycentric[2] * mesh.positions[tri[2]];
    EXPECT_LT((from_bary - on_ray).norm(), 1e-9) << "ray " << i;
    EXPECT_NEAR(hit->barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(hit->barycentric.minCoeff(), 0.0);
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
    if (hit->triangle == ref.triangle) {
      EXPECT_LT((hit->barycentric - ref.barycentric).norm(), 1e-9) << "ray " << i;
    }
  }
  EXPECT_GT(hits, count / 10);  // the test must actually exercise hits
}

}  // namespace

TEST(RayCaster, EqualsBruteForceOnIcosphere) {
  expect_equal_to_brute_force(make_icosphere(Vec3(0.1, 0.2, -0.1), 1.7, 3), 3000, 11);
}

TEST(RayCaster, EqualsBruteForceOnBox) {
  expect_equal_to_brute_force(make_box_mesh(Vec3(-1.2, -0.7, -1.5), Vec3(1.1, 1.3, 0.9), 3), 3000, 12);
}

TEST(RayCaster, EqualsBruteForceOnSphereWithHole) {
  expect_equal_to_brute_force(sphere_with_hole(), 3000, 13);
}

TEST(RayCaster, RayThroughHoleMisses) {
  const TriMesh open = sphere_with_hole();
  const TriMesh closed = make_icosphere(Vec3(0.3, -0.2, 0.1), 1.5, 3);
  // Aim from the centre through the centroid of a removed triangle.
  const Tri& gone = closed.triangles[6];
  const Vec3 c = (closed.positions[gone[0]] + closed.positions[gone[1]] + closed.positions[gone[2]]) / 3.0;
  const Vec3 centre(0.3, -0.2, 0.1);
  EXPECT_TRUE(RayCaster(closed).intersect(centre, c - centre).has_value());
  EXPECT_FALSE(RayCaster(open).intersect(centre, c - centre).has_value());
}

TEST(RayCaster, FaceCullingPicksTheRightSide) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 4);
  const RayCaster caster(sphere);
  const Vec3 outside(0.05, 0.02, 5.0);
  const Vec3 down(0, 0, -1);
  const auto front = caster.intersect(outside, down, 0.0, 1e9, FaceCulling::back);
  ASSERT_TRUE(front);
  EXPECT_NEAR(front->t, 4.0, 0.01);
  EXPECT_LT(front->normal.dot(down), 0.0);
  const auto back = caster.intersect(outside, down, 0.0, 1e9, FaceCulling::front);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->t, 6.0, 0.01);
  EXPECT_GT(back->normal.dot(down), 0.0);
  // From inside, every hit is on a back face.
  EXPECT_FALSE(caster.intersect(Vec3::Zero(), down, 0.0, 1e9, FaceCulling::back));
  EXPECT_FALSE(caster.occluded(Vec3::Zero(), down, 0.0, 1e9, FaceCulling::back));
  EXPECT_TRUE(caster.intersect(Vec3::Zero(), down, 0.0, 1e9, FaceCulling::front));
}

TEST(RayCaster, TRangeIsRespected) {
  const RayCaster caster(make_icosphere(Vec3::Zero(), 1.0, 3));
  const Vec3 o(0, 0, -3);
  const Vec3 d(0, 0, 1);
  const auto near = caster.intersect(o, d);
  ASSERT_TRUE(near);
  const auto far = caster.intersect(o, d, near->t + 0.1);
  ASSERT_TRUE(far);
  EXPECT_GT(far->t, 3.9);
  EXPECT_FALSE(caster.intersect(o, d, 0.0, near->t - 0.1));
  EXPECT_FALSE(caster.occluded(o, d, 0.0, near->t - 0.1));
  EXPECT_TRUE(caster.occluded(o, d, 0.0, near->t + 0.1));
}

TEST(RayCaster, RaysFromTheSurfaceReportTInTheirRange) {
  // Rays starting on the surface itself (a vertex moved along its normal onto the mesh it lies on): Embree accepts
  // the hit in float, and the refinement in double must not report a t below t_min (or above t_max).
  TriMesh mesh = make_icosphere(Vec3(40.0, -25.0, 300.0), 80.0, 4);
  const RayCaster caster(mesh);
  RandomStream rng(7, 0);
  std::size_t hits = 0;
  for (const Tri& f : mesh.triangles) {
    const double u = rng.uniform(0.0, 1.0), v = rng.uniform(0.0, 1.0 - u);
    const Vec3& a = mesh.positions[f[0]];
    const Vec3& b = mesh.positions[f[1]];
    const Vec3& c = mesh.positions[f[2]];
    const Vec3 p = (1.0 - u - v) * a + u * b + v * c;
    const Vec3 n = (b - a).cross(c - a).normalized();
    for (const double sign : {1.0, -1.0}) {
      const double t_max = 0.5 + rng.uniform(0.0, 1.0);
      const auto hit = caster.intersect(p, sign * n, 0.0, t_max);
      if (!hit) continue;
      ++hits;
      ASSERT_GE(hit->t, 0.0);
      ASSERT_LE(hit->t, t_max);
    }
  }
  EXPECT_GT(hits, 0u);
}

TEST(RayCaster, BatchAndOccludedAgreeWithSingleQueries) {
  const TriMesh mesh = sphere_with_hole();
  const RayCaster caster(mesh);
  RandomStream rng(21, 0);
  std::vector<Vec3> origins, directions;
  for (int i = 0; i < 2000; ++i) {
    origins.emplace_back(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    directions.push_back(random_unit(rng));
  }
  const auto batch = caster.intersect_batch(origins, directions, 0.0, 2.0);
  ASSERT_EQ(batch.size(), origins.size());
  for (std::size_t i = 0; i < origins.size(); ++i) {
    const auto single = caster.intersect(origins[i], directions[i], 0.0, 2.0);
    ASSERT_EQ(single.has_value(), batch[i].has_value());
    EXPECT_EQ(caster.occluded(origins[i], directions[i], 0.0, 2.0), single.has_value());
    if (single) {
      EXPECT_EQ(single->triangle, batch[i]->triangle);
      EXPECT_EQ(single->t, batch[i]->t);
    }
  }
}

TEST(RayCaster, FarFromOriginKeepsDoublePrecision) {
  // A scan placed far from the origin (float would lose ~0.1 mm here); refinement restores double.
  const Vec3 centre(1.0e5, -2.0e5, 3.0e4);
  const TriMesh sphere = make_icosphere(centre, 10.0, 3);
  const RayCaster caster(sphere);
  const Vec3 o = centre + Vec3(0.3, 0.1, -40.0);
  const Vec3 d(0, 0, 1);
  const auto hit = caster.intersect(o, d);
  ASSERT_TRUE(hit);
  const BruteHit ref = brute_force(sphere, o, d);
  EXPECT_EQ(hit->triangle, ref.triangle);
  EXPECT_NEAR(hit->t, ref.t, 1e-9);
}

TEST(RayCaster, EmptyMeshAndBadRays) {
  const RayCaster empty{TriMesh{}};
  EXPECT_FALSE(empty.intersect(Vec3::Zero(), Vec3(1, 0, 0)));
  const RayCaster caster(make_icosphere(Vec3::Zero(), 1.0, 1));
  EXPECT_THROW((void)caster.intersect(Vec3::Zero(), Vec3::Zero()), InputError);
  EXPECT_THROW((void)caster.intersect(Vec3::Zero(), Vec3(1, 0, 0), 2.0, 1.0), InputError);
  EXPECT_THROW((void)caster.intersect(Vec3(std::nan(""), 0, 0), Vec3(1, 0, 0)), InputError);
  EXPECT_THROW((void)caster.intersect_batch({Vec3::Zero()}, {}), InputError);
  TriMesh bad = make_icosphere(Vec3::Zero(), 1.0, 0);
  bad.triangles[3][1] = 999;
  EXPECT_THROW(RayCaster{bad}, InputError);
}

TEST(RayCaster, BatchIsIdenticalAtAnyThreadCount) {
  const RayCaster caster(make_icosphere(Vec3::Zero(), 1.0, 3));
  RandomStream rng(22, 0);
  std::vector<Vec3> origins, directions;
  for (int i = 0; i < 1000; ++i) {
    origins.emplace_back(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    directions.push_back(random_unit(rng));
  }
  const auto many = caster.intersect_batch(origins, directions);
  set_thread_count(1);
  const auto one = caster.intersect_batch(origins, directions);
  set_thread_count(0);
  for (std::size_t i = 0; i < origins.size(); ++i) {
    ASSERT_EQ(many[i].has_value(), one[i].has_value());
    if (many[i]) {
      EXPECT_EQ(many[i]->triangle, one[i]->triangle);
      EXPECT_EQ(many[i]->t, one[i]->t);
    }
  }
}

TEST(RayCaster, FreeFunctionMatchesCaster) {
  const TriMesh mesh = make_box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1), 2);
  const RayCaster caster(mesh);
  RandomStream rng(23, 0);
  for (int i = 0; i < 300; ++i) {
    const Vec3 o(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const Vec3 d = random_unit(rng);
    for (const FaceCulling culling : {FaceCulling::none, FaceCulling::back, FaceCulling::front}) {
      const auto a = caster.intersect(o, d, 0.0, 10.0, culling);
      const auto b = intersect_ray(mesh, o, d, 0.0, 10.0, culling);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (a) {
        EXPECT_NEAR(a->t, b->t, 1e-9);
        EXPECT_LT((a->point - b->point).norm(), 1e-9);
        EXPECT_TRUE(a->normal.isApprox(b->normal));
      }
    }
  }
}
