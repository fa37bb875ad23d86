#pragma once
/// Property checks shared by the quick (nested spheres) and slow (arm, head phantoms) suites: volume
/// conservation, bone volume, positive tets, labels against winding numbers, Hausdorff distance to the skin.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include "core/error.hpp"
#include "core/random.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"
#include "hausdorff.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/winding_number.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"

using namespace forensim;  // NOLINT: test-only header, included once per test program

namespace tet_test {

struct Meshed {
  TriMesh skin, bone;
  TetMesh tets;
  TetrahedralizeReport report;
  double edge = 0.0;
};

/// Surfaces ("spheres", or a phantom name) and their tet mesh at a coarse size, built once for all tests.
inline const Meshed& coarse(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Meshed>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<Meshed>();
    TetrahedralizeOptions options;
    if (name == "spheres") {
      // A ball of flesh around an off-centre ball of bone: small enough for the quick suite.
      slot->skin = make_icosphere(Vec3::Zero(), 30.0, 4);
      slot->bone = make_icosphere(Vec3(4, -2, 1), 15.0, 4);
      options.edge_length_mm = slot->edge = 6.0;
      options.surface_distance_fraction = 0.02;
    } else {
      const auto phantom = make_phantom(name);
      slot->skin = phantom_surface(*phantom, PhantomSurface::skin, 3.0);
      slot->bone = phantom_surface(*phantom, PhantomSurface::bone, 2.0);
      // Finer than the head: the arm's fingers are about 16 mm thick.
      options.edge_length_mm = slot->edge = name == "arm" ? 8.0 : 12.0;
    }
    slot->tets = tetrahedralize(slot->skin, {slot->bone}, options, &slot->report);
    std::printf("%s:\n%s%s", name.c_str(), slot->report.summary().c_str(), tet_quality(slot->tets).summary().c_str());
  }
  return *slot;
}

inline void check_volume_matches_the_skin_within_one_percent(const Meshed& m) {
  const double skin = enclosed_volume(m.skin);
  EXPECT_NEAR(tet_mesh_volume(m.tets), skin, 0.01 * skin);
  EXPECT_NEAR(m.report.tet_volume_mm3, tet_mesh_volume(m.tets), 1e-6 * skin);
}

inline void check_bone_volume_matches_the_bones_within_two_percent(const Meshed& m) {
  const double bone = enclosed_volume(m.bone);
  ASSERT_GT(bone, 0.0);
  EXPECT_NEAR(tet_mesh_volume(m.tets, tissue_bone), bone, 0.02 * bone);
}

inline void check_every_tet_is_positive_and_labelled(const Meshed& m) {
  ASSERT_GT(m.tets.tet_count(), 100u);
  EXPECT_NO_THROW(m.tets.validate("tets"));
  ASSERT_EQ(m.tets.tet_labels.size(), m.tets.tet_count());
  for (std::size_t t = 0; t < m.tets.tet_count(); ++t) {
    const Tet& k = m.tets.tets[t];
    ASSERT_GT(tet_signed_volume(m.tets.positions[k[0]], m.tets.positions[k[1]], m.tets.positions[k[2]],
                                m.tets.positions[k[3]]),
              0.0)
        << "tet " << t;
    ASSERT_TRUE(m.tets.tet_labels[t] == tissue_flesh || m.tets.tet_labels[t] == tissue_bone);
  }
  const TetQualityReport q = tet_quality(m.tets);
  EXPECT_EQ(q.inverted_count, 0u);
  EXPECT_EQ(q.flat_count, 0u);
  EXPECT_GT(q.dihedral_min, 1.0);
  // Every node is used by a tet.
  std::vector<char> used(m.tets.vertex_count(), 0);
  for (const Tet& k : m.tets.tets)
    for (Index v : k) used[static_cast<std::size_t>(v)] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

inline void check_labels_agree_with_point_in_mesh_tests(const Meshed& m) {
  const WindingNumber bone(m.bone);
  RandomStream rng(7, 0);
  std::vector<Vec3> samples;
  std::vector<int> labels;
  for (int i = 0; i < 2000; ++i) {
    const std::size_t t =
        static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(m.tets.tet_count()) - 1));
    // Random barycentric point of a random tet.
    double w[4], sum = 0.0;
    for (double& x : w) sum += (x = -std::log(rng.uniform(1e-12, 1.0)));
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 4; ++c) p += (w[c] / sum) * m.tets.positions[static_cast<std::size_t>(m.tets.tets[t][c])];
    samples.push_back(p);
    labels.push_back(m.tets.tet_labels[t]);
  }
  const std::vector<bool> inside = bone.inside_batch(samples);
  int agree = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) agree += (inside[i] == (labels[i] == tissue_bone)) ? 1 : 0;
  EXPECT_GE(agree, 0.98 * static_cast<double>(samples.size()));
}

inline void check_boundary_lies_within_an_edge_length_of_the_skin(const Meshed& m) {
  const TriMesh boundary = tet_boundary_mesh(m.tets);
  EXPECT_LT(tet_test::one_way_distance(boundary, m.skin), m.edge);
  EXPECT_LT(tet_test::one_way_distance(m.skin, boundary), m.edge);
  EXPECT_TRUE(check_topology(boundary).is_closed());
}

}  // namespace tet_test

// One test per model: the model is built once per test process (ctest runs each test in its own), and the
// phantoms take about a minute each to mesh.
class ModelTets : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelTets, VolumesTetsLabelsAndBoundaryMeetTheirTolerances) {
  const tet_test::Meshed& m = tet_test::coarse(GetParam());
  {
    SCOPED_TRACE("volume matches the skin within one percent");
    tet_test::check_volume_matches_the_skin_within_one_percent(m);
  }
  {
    SCOPED_TRACE("bone volume matches the bones within two percent");
    tet_test::check_bone_volume_matches_the_bones_within_two_percent(m);
  }
  {
    SCOPED_TRACE("every tet is positive and labelled");
    tet_test::check_every_tet_is_positive_and_labelled(m);
  }
  {
    SCOPED_TRACE("labels agree with point in mesh tests");
    tet_test::check_labels_agree_with_point_in_mesh_tests(m);
  }
  {
    SCOPED_TRACE("boundary lies within an edge length of the skin");
    tet_test::check_boundary_lies_within_an_edge_length_of_the_skin(m);
  }
}
