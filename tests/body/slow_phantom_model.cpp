// Slow suite: body models of the phantoms at the named sizes. The `paper` sizes must reproduce Table 1 of
// Frerichs et al. 2020 within 10 % (nodes, tets, skin triangles), and every model must tie each skin vertex
// to the volume so that the tracking points on the rest volume give back the stored distances.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "body/body_model_io.hpp"
#include "body/phantom_model.hpp"
#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/tet_boundary.hpp"
#include "spatial/closest_point.hpp"
#include "support/test_support.hpp"
#include "tetrahedralize/tet_quality.hpp"

using namespace forensim;

namespace {

void expect_tracking_consistent(const BodyModel& model) {
  ASSERT_EQ(model.tracking.size(), model.skin.vertex_count()) << "every skin vertex needs a tracking point";
  const std::vector<Vec3> points = tracking_points(model.tracking, model.volume.positions);
  const ClosestPointQuery boundary(tet_boundary_mesh(model.volume));
  const auto on_boundary = boundary.query_batch(points);
  std::size_t far = 0, wrong = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = (points[i] - model.skin.positions[i]).norm();
    if (std::abs(d - model.tracking.rest_distance[i]) > 1e-9 * (1.0 + d)) ++wrong;
    // The tracking point lies on the volume's boundary.
    if (!on_boundary[i] || on_boundary[i]->distance > 1e-6) ++far;
  }
  EXPECT_EQ(wrong, 0u) << "tracking points that do not give back their stored distance";
  EXPECT_EQ(far, 0u) << "tracking points off the volume boundary";
}

}  // namespace

class PhantomModelSizes : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(PhantomModelSizes, CountsTrackingAndVolume) {
  const auto& [phantom, size_name] = GetParam();
  const PhantomModelSize size = phantom_model_size(phantom, size_name);
  PhantomModelReport report;
  const BodyModel model = make_phantom_model(size, {}, &report);
  std::printf("%s %s:\n%s", phantom.c_str(), size_name.c_str(), report.summary().c_str());
  const auto nodes = static_cast<double>(model.volume.vertex_count());
  const auto tets = static_cast<double>(model.volume.tet_count());
  const auto skin = static_cast<double>(model.skin.triangle_count());
  std::printf("counts: %.0f nodes, %.0f tets, %.0f skin triangles\n", nodes, tets, skin);
  EXPECT_NEAR(nodes, static_cast<double>(size.volume_nodes), 0.1 * static_cast<double>(size.volume_nodes));
  EXPECT_NEAR(skin, static_cast<double>(size.skin_triangles), 0.1 * static_cast<double>(size.skin_triangles));
  if (size_name == "paper") {
    EXPECT_NEAR(nodes, static_cast<double>(size.paper_nodes), 0.1 * static_cast<double>(size.paper_nodes));
    EXPECT_NEAR(tets, static_cast<double>(size.paper_tets), 0.1 * static_cast<double>(size.paper_tets));
    EXPECT_NEAR(skin, static_cast<double>(size.paper_skin_triangles),
                0.1 * static_cast<double>(size.paper_skin_triangles));
  }
  // The bounds (1 % of the volume, 2 % of the bone) hold from the paper size up; the small size, a few
  // thousand nodes for quick looks, cuts the fingers' and the skull's curvature more coarsely.
  const bool small = size_name == "small";
  EXPECT_NEAR(report.volume.tet_volume_mm3, report.volume.skin_volume_mm3,
              (small ? 0.02 : 0.01) * report.volume.skin_volume_mm3);
  EXPECT_NEAR(report.volume.bone_tet_volume_mm3, report.volume.bone_volume_mm3,
              (small ? 0.06 : 0.02) * report.volume.bone_volume_mm3);
  EXPECT_EQ(tet_quality(model.volume).inverted_count, 0u);
  EXPECT_EQ(model.skin_vertex_parts.size(), model.skin.vertex_count());
  EXPECT_GT(report.tracking.ray_fraction(), 0.95);
  expect_tracking_consistent(model);
  if (small) {
    // The folder round trip keeps the model as built.
    const auto folder = test::scratch_dir("phantom_model") / (phantom + "_small");
    write_body_model(folder, model);
    const BodyModel back = read_body_model(folder);
    EXPECT_EQ(back.volume.tets, model.volume.tets);
    EXPECT_EQ(back.tracking.weights, model.tracking.weights);
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, PhantomModelSizes,
                         ::testing::Values(std::make_pair("arm", "small"), std::make_pair("head", "small"),
                                           std::make_pair("arm", "paper"), std::make_pair("head", "paper")),
                         [](const auto& p) { return p.param.first + "_" + p.param.second; });

TEST(PhantomModelSize, KnowsTheSizesAndRejectsOthers) {
  EXPECT_EQ(phantom_model_size("arm", "paper").paper_tets, 141000u);
  EXPECT_EQ(phantom_model_size("head", "paper").paper_skin_triangles, 122000u);
  EXPECT_THROW(phantom_model_size("foot", "paper"), InputError);
  EXPECT_THROW(phantom_model_size("arm", "huge"), InputError);
}
