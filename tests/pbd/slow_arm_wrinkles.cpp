// Slow suite: the skin of the small arm body model over a shrinking volume. The flesh shrinks towards the bones
// while the skin dries from a moisture ratio of 1 to 0.12 (between the slippage thresholds of eq. 35, so the
// tracking stiffness falls to 0.4 and the slip radius r_j = (1 - k_j / k_t) r_max of eq. 33 opens to 0.6 r_max):
// every node of the
// volume's outer boundary moves towards its closest bone point until the flesh is 30 % as thick (eq. 28 with
// forensim's default tissue gives fully dried flesh about 20 % of its volume), the displacement smoothed over
// the boundary so that the closest-point map's creases between bones do not show; the skin is stepped through
// it with each of Figure 8's wrinkle controls (Frerichs, Vidler and Gatzidis 2020). The wrinkles are measured
// against the skin glued to the shrunk volume (each vertex at its tracking point plus its rest offset): the RMS
// of the fine part (what Taubin smoothing removes) of the skin's lift-off from the glued skin along its normal,
// so the shape of the shrunk arm itself, the same for every set, does not count. Checks: that measure grows over the
// three sets by a clear margin, the skin follows the flesh down to the bones of the hand and wrist (the skin-to-bone
// distance there falls by at least half), and no skin triangle turns over. Writes a picture of the three arms
// side by side to the test's scratch folder.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "body/phantom_model.hpp"
#include "body/tracking.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/tet_boundary.hpp"
#include "image/png_io.hpp"
#include "pbd/skin_simulation.hpp"
#include "pbd/wrinkle_measure.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "spatial/closest_point.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

constexpr double flesh_left = 0.3;       // flesh thickness at the end, as a fraction of the rest thickness
constexpr double final_moisture = 0.12;  // moisture ratio of the skin at the end
constexpr int shrink_steps = 120, settle_steps = 40;

struct Arm {
  BodyModel body;
  TriMesh bone;
  std::vector<Vec3> full_displacement;   ///< #V boundary nodes' displacement when fully shrunk (0 inside)
  std::vector<std::uint8_t> hand_wrist;  ///< #S skin vertices of the palm and wrist
};

const Arm& arm() {
  static const Arm a = [] {
    Arm out;
    out.body = make_phantom_model(phantom_model_size("arm", "small"));
    out.bone = tet_boundary_mesh(out.body.volume, tissue_bone);
    std::vector<std::uint8_t> on_bone(out.body.volume.vertex_count(), 0);
    for (std::size_t t = 0; t < out.body.volume.tet_count(); ++t)
      if (out.body.volume.label(t) == tissue_bone)
        for (Index v : out.body.volume.tets[t]) on_bone[static_cast<std::size_t>(v)] = 1;
    const ClosestPointQuery bone(out.bone);
    const auto closest = bone.query_batch(out.body.volume.positions);
    // Full-shrinkage displacement of the outer boundary's nodes, smoothed over the boundary (10 Jacobi passes).
    const std::size_t nv = out.body.volume.vertex_count();
    std::vector<Vec3> d(nv, Vec3::Zero());
    std::vector<std::vector<Index>> neighbours(nv);
    std::vector<std::uint8_t> on_boundary(nv, 0);
    for (const TetFace& f : out.body.boundary_faces)
      for (int k = 0; k < 3; ++k) {
        on_boundary[static_cast<std::size_t>(f.vertices[k])] = 1;
        neighbours[static_cast<std::size_t>(f.vertices[k])].push_back(f.vertices[(k + 1) % 3]);
      }
    for (std::size_t i = 0; i < nv; ++i)
      if (on_boundary[i] && !on_bone[i] && closest[i])
        d[i] = (1.0 - flesh_left) * (closest[i]->point - out.body.volume.positions[i]);
    for (int pass = 0; pass < 10; ++pass) {
      std::vector<Vec3> next = d;
      for (std::size_t i = 0; i < nv; ++i) {
        if (!on_boundary[i] || on_bone[i] || neighbours[i].empty()) continue;
        Vec3 mean = Vec3::Zero();
        for (Index j : neighbours[i]) mean += d[static_cast<std::size_t>(j)];
        next[i] = 0.5 * d[i] + 0.5 * mean / static_cast<double>(neighbours[i].size());
      }
      d.swap(next);
    }
    out.full_displacement = d;
    for (int part : out.body.skin_vertex_parts) {
      const std::string& name = out.body.part_names[static_cast<std::size_t>(part)];
      out.hand_wrist.push_back(name == "palm" || name == "wrist");
    }
    return out;
  }();
  return a;
}

std::vector<Vec3> shrunk_nodes(const Arm& a, double f) {
  std::vector<Vec3> nodes = a.body.volume.positions;
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] += f * a.full_displacement[i];
  return nodes;
}

double mean_bone_distance(const Arm& a, const std::vector<Vec3>& skin) {
  const ClosestPointQuery bone(a.bone);
  const auto closest = bone.query_batch(skin);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < skin.size(); ++i) {
    if (!a.hand_wrist[i] || !closest[i]) continue;
    sum += closest[i]->distance;
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

std::size_t flipped_triangles(const std::vector<Tri>& triangles, const std::vector<Vec3>& rest,
                              const std::vector<Vec3>& now) {
  std::size_t count = 0;
  for (const Tri& t : triangles) {
    const Vec3 n0 = (rest[t[1]] - rest[t[0]]).cross(rest[t[2]] - rest[t[0]]);
    const Vec3 n1 = (now[t[1]] - now[t[0]]).cross(now[t[2]] - now[t[0]]);
    if (n0.dot(n1) <= 0.0) ++count;
  }
  return count;
}

/// The skin glued to the volume at `nodes`: each vertex at its tracking point plus its rest offset.
std::vector<Vec3> glued_skin(const Arm& a, const std::vector<Vec3>& nodes) {
  const std::vector<Vec3> t0 = tracking_points(a.body.tracking, a.body.volume.positions);
  const std::vector<Vec3> t1 = tracking_points(a.body.tracking, nodes);
  std::vector<Vec3> glued(t1.size());
  for (std::size_t i = 0; i < glued.size(); ++i) glued[i] = t1[i] + (a.body.skin.positions[i] - t0[i]);
  return glued;
}

double wrinkle_height(const Arm& a, const std::vector<Vec3>& skin, const std::vector<Vec3>& glued) {
  return wrinkle_height_mm(skin, glued, a.body.skin.triangles);
}

struct Result {
  WrinkleMeasure wrinkles;
  double wrinkle_height_mm = 0.0;
  std::vector<Vec3> positions;
  double bone_distance_mm = 0.0;
  std::size_t flipped = 0;
  double seconds_per_step = 0.0;
};

Result run(const Arm& a, const WrinkleControls& controls, SkinSettings settings = {}) {
  settings.wrinkle = controls;
  const SkinModel model = make_skin_model(a.body, settings);
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  double seconds = 0.0;
  for (int s = 1; s <= shrink_steps + settle_steps; ++s) {
    const double f = std::min(1.0, static_cast<double>(s) / shrink_steps);
    const std::vector<double> moisture(model.vertex_count(), 1.0 - (1.0 - final_moisture) * f);
    seconds += sim.step(state, shrunk_nodes(a, f), moisture, 1.0 / 30.0).seconds;
  }
  Result r;
  r.wrinkles = wrinkle_measure(state.positions, model.triangles);
  r.wrinkle_height_mm = wrinkle_height(a, state.positions, glued_skin(a, shrunk_nodes(a, 1.0)));
  r.positions = state.positions;
  r.bone_distance_mm = mean_bone_distance(a, state.positions);
  r.flipped = flipped_triangles(model.triangles, model.vertex_rest_position, state.positions);
  r.seconds_per_step = seconds / (shrink_steps + settle_steps);
  std::printf(
      "r_max %.3f (%.2f mm), damping %.2f: wrinkle height %.4f mm, skin RMS %.4f mm, mean |H| %.5f /mm, hand/wrist "
      "skin-bone %.2f mm, %zu flipped triangles, %.2f ms per step\n",
      controls.r_max_relative, model.r_max_mm, controls.damping, r.wrinkle_height_mm, r.wrinkles.rms_smooth_distance_mm,
      r.wrinkles.mean_abs_curvature_per_mm, r.bone_distance_mm, r.flipped, 1e3 * r.seconds_per_step);
  return r;
}

}  // namespace

TEST(SlowArmWrinkles, Figure8SetsWrinkleMoreAndSkinClingsToTheBones) {
  const Arm& a = arm();
  ASSERT_FALSE(a.bone.triangles.empty());
  const double rest_distance = mean_bone_distance(a, a.body.skin.positions);
  const WrinkleMeasure rest = wrinkle_measure(a.body.skin.positions, a.body.skin.triangles);
  // The volume alone (skin glued to its tracking points) shows how much roughness the shrinkage itself makes.
  std::printf("skin: %zu vertices; rest: wrinkle RMS %.4f mm, mean |H| %.5f /mm, hand/wrist skin-bone %.2f mm\n",
              a.body.skin.vertex_count(), rest.rms_smooth_distance_mm, rest.mean_abs_curvature_per_mm, rest_distance);
  // The skin glued to the shrunk volume: the roughness the shrinkage alone gives, for comparison.
  const std::vector<Vec3> glued = glued_skin(a, shrunk_nodes(a, 1.0));
  const WrinkleMeasure glued_measure = wrinkle_measure(glued, a.body.skin.triangles);
  std::printf("glued to the shrunk volume: wrinkle RMS %.4f mm, mean |H| %.5f /mm, hand/wrist skin-bone %.2f mm\n",
              glued_measure.rms_smooth_distance_mm, glued_measure.mean_abs_curvature_per_mm,
              mean_bone_distance(a, glued));
  std::vector<Result> results;
  for (int set = 0; set < 3; ++set) results.push_back(run(a, WrinkleControls::figure8(set)));
  // The wrinkles grow over the sets by at least 1.3 from set to set (measured 0.075, 0.140 and 0.239 mm).
  EXPECT_GT(results[1].wrinkle_height_mm, 1.3 * results[0].wrinkle_height_mm);
  EXPECT_GT(results[2].wrinkle_height_mm, 1.3 * results[1].wrinkle_height_mm);
  EXPECT_GT(results[0].wrinkle_height_mm, 0.0);

  std::vector<SheetCell> cells;
  for (int set = 0; set < 3; ++set) {
    TriMesh skin;
    skin.positions = results[set].positions;
    skin.triangles = a.body.skin.triangles;
    compute_normals(skin);
    Scene scene;
    scene.add(skin, SurfaceMaterial::skin());
    scene.frame(ViewName::front, 3.0);
    RenderSettings settings;
    settings.width = 720;
    settings.height = 240;
    settings.samples_per_pixel = 4;
    const WrinkleControls c = WrinkleControls::figure8(set);
    char caption[128];
    std::snprintf(caption, sizeof caption, "r_max %.3f, damping %.2f: %.3f mm", c.r_max_relative, c.damping,
                  results[set].wrinkle_height_mm);
    cells.push_back({Renderer(scene).render(settings), caption});
  }
  const auto dir = test::scratch_dir("pbd_arm_wrinkles");
  write_png(dir / "figure8_arms.png", make_sheet(cells, 1, "Figure 8 wrinkle controls on the dried small arm"));
  std::cout << "picture in " << dir << "\n";
  for (const Result& r : results) {
    EXPECT_LE(r.bone_distance_mm, 0.5 * rest_distance);
    EXPECT_EQ(r.flipped, 0u);
  }
}
