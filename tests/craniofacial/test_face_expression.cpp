#include "craniofacial/face_expression.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/skin_spring_kernels.hpp"
#include "support/test_support.hpp"
#include "template_head_fixture.hpp"

namespace forensim {
namespace {

const FaceExpressions& expressions() {
  static const FaceExpressions e = [] {
    const TemplateHead& head = test::coarse_template_head();
    return FaceExpressions(head.skin, head.skull, shape_muscles(head.muscles, head.skin));
  }();
  return e;
}

Vec3 skin_landmark(const std::string& name) {
  for (const TemplateSkinLandmark& l : test::coarse_template_head().skin_landmarks) {
    if (l.name == name) return l.position;
  }
  ADD_FAILURE() << "no skin landmark " << name;
  return Vec3::Zero();
}

/// Presets solved once per test program.
const FaceExpression& cached_preset(const std::string& name) {
  static std::map<std::string, FaceExpression> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, expressions().preset(name)).first;
  return it->second;
}

std::vector<Vec3> track(const FaceExpression& e, const std::vector<Vec3>& points) {
  return track_skin_points(test::coarse_template_head().skin, e.skin_positions, points);
}

TEST(SkinSpringKernels, SpringGradientAndHessianMatchFiniteDifferences) {
  const Vec3 a(0.3, -0.2, 1.1), b(-0.5, 0.4, 0.2);
  const double rest = 0.8, k = 2.5, h = 1e-6;
  const SpringTerm t = spring_term(a, b, rest, k, false, false);
  Vec6 x;
  x << a, b;
  for (int i = 0; i < 6; ++i) {
    Vec6 xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    const SpringTerm tp = spring_term(xp.head<3>(), xp.tail<3>(), rest, k, false, false);
    const SpringTerm tm = spring_term(xm.head<3>(), xm.tail<3>(), rest, k, false, false);
    EXPECT_NEAR((tp.energy - tm.energy) / (2 * h), t.gradient(i), 1e-6);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR((tp.gradient(j) - tm.gradient(j)) / (2 * h), t.hessian(j, i), 1e-5);
  }
  // Compressed: the projected Hessian is positive semi-definite, a tension-only spring is slack.
  const SpringTerm c = spring_term(a, b, 3.0, k, false, true);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat6>(c.hessian).eigenvalues().minCoeff(), -1e-12);
  const SpringTerm slack = spring_term(a, b, 3.0, k, true, true);
  EXPECT_EQ(slack.energy, 0.0);
  EXPECT_EQ(slack.gradient.norm(), 0.0);
  // The Hessian-free force of the quasi-Newton solver is the same energy and gradient.
  for (double r : {rest, 3.0}) {
    const SpringForce f = spring_force(a, b, r, k);
    const SpringTerm full = spring_term(a, b, r, k, false, false);
    EXPECT_NEAR(f.energy, full.energy, 1e-14);
    EXPECT_LT((f.gradient_a - full.gradient.head<3>()).norm(), 1e-14);
  }
  EXPECT_EQ(spring_force(a, a, rest, k).gradient_a.norm(), 0.0);
}

TEST(MuscleContraction, EnergyGradientMatchesFiniteDifferences) {
  const MuscleContractionSolver& solver = expressions().solver();
  const SkinMuscleModel& m = solver.model();
  std::vector<double> act(m.muscle_names.size(), 0.0);
  for (std::size_t k = 0; k < act.size(); ++k) act[k] = 0.1 + 0.8 * static_cast<double>(k % 5) / 4.0;
  std::vector<Vec3> x = m.node_rest_positions;
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] += 0.3 * Vec3(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(2.1 * i));
  std::vector<double> g;
  solver.energy(x, act, &g);
  const double h = 1e-6;
  // Nodes: a skin vertex, a free fibre sample (the last one) and its skin attachment corner.
  const std::size_t nodes[] = {0, x.size() - 1, static_cast<std::size_t>(m.attachment_triangle.back()[0])};
  for (std::size_t n : nodes) {
    for (int r = 0; r < 3; ++r) {
      std::vector<Vec3> xp = x, xm = x;
      xp[n](r) += h;
      xm[n](r) -= h;
      const double fd = (solver.energy(xp, act) - solver.energy(xm, act)) / (2 * h);
      EXPECT_NEAR(fd, g[3 * n + static_cast<std::size_t>(r)], 1e-5 * std::max(1.0, std::abs(fd))) << n << " " << r;
    }
  }
}

TEST(FaceExpression, NeutralLeavesSkinExactlyInPlace) {
  const FaceExpression e = cached_preset("neutral");
  const TriMesh& skin = test::coarse_template_head().skin;
  ASSERT_EQ(e.skin_positions.size(), skin.positions.size());
  for (std::size_t i = 0; i < skin.positions.size(); ++i) ASSERT_EQ(e.skin_positions[i], skin.positions[i]) << i;
  EXPECT_EQ(e.newton_iterations, 0);
}

TEST(FaceExpression, LinearMusclePullsInsertionTowardOriginAndLeavesBackOfHeadStill) {
  const TemplateHead& head = test::coarse_template_head();
  const FaceExpression e = expressions().pose("zyg", {{"zygomaticus_major_L", 1.0}});
  const MuscleLayout* zyg = nullptr;
  for (const MuscleLayout& m : head.muscles) {
    if (m.name == "zygomaticus_major_L") zyg = &m;
  }
  ASSERT_NE(zyg, nullptr);
  const int mid = zyg->fibre_count / 2;
  const Vec3 origin = zyg->grid[static_cast<std::size_t>(mid * zyg->samples_per_fibre)];
  const Vec3 insertion = zyg->grid[static_cast<std::size_t>((mid + 1) * zyg->samples_per_fibre - 1)];
  const auto shaped = shape_muscles({*zyg}, head.skin);
  const Vec3 at = shaped[0].skin_points[static_cast<std::size_t>((mid + 1) * zyg->samples_per_fibre - 1)];
  const Vec3 moved = track(e, {at})[0];
  const Vec3 toward = (origin - insertion).normalized();
  EXPECT_GT((moved - at).dot(toward), 1.0) << "insertion moved " << (moved - at).transpose();
  EXPECT_GT((moved - at).dot(toward), 0.7 * (moved - at).norm());
  // The mirrored insertion on the right moves less; the back of the head stays.
  const Vec3 mirror_at(-at.x(), at.y(), at.z());
  EXPECT_LT((track(e, {mirror_at})[0] - mirror_at).norm(), 0.5 * (moved - at).norm());
  double back = 0.0;
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    if (head.skin.positions[i].y() > 40.0) back = std::max(back, (e.skin_positions[i] - head.skin.positions[i]).norm());
  }
  EXPECT_LT(back, 0.05 * (moved - at).norm());  // within the Newton tolerance of zero
}

TEST(FaceExpression, SmileRaisesAndWidensMouthCornersSymmetrically) {
  const Vec3 left = skin_landmark("ch'_L"), right = skin_landmark("ch'_R");
  const auto moved = track(cached_preset("smile"), {left, right});
  const Vec3 dl = moved[0] - left, dr = moved[1] - right;
  EXPECT_GT(dl.z(), 1.0);
  EXPECT_GT(dr.z(), 1.0);
  EXPECT_GT(dl.x(), 0.5);   // the left corner moves further left (+x)
  EXPECT_LT(dr.x(), -0.5);  // the right one further right
  // Mirror symmetry of the template: x flips, y and z agree.
  const Vec3 dr_mirrored(-dr.x(), dr.y(), dr.z());
  EXPECT_LT((dl - dr_mirrored).norm(), 0.2 * dl.norm()) << dl.transpose() << " vs " << dr.transpose();
}

TEST(FaceExpression, SphincterNarrowsTheMouth) {
  const Vec3 left = skin_landmark("ch'_L"), right = skin_landmark("ch'_R");
  const auto moved = track(expressions().pose("pucker", {{"orbicularis_oris", 1.0}}), {left, right});
  EXPECT_LT((moved[0] - moved[1]).norm(), (left - right).norm() - 1.0);
}

TEST(FaceExpression, FrownLowersMouthCornersAndSurpriseRaisesTheBrows) {
  const Vec3 corner = skin_landmark("ch'_L");
  EXPECT_LT(track(cached_preset("frown"), {corner})[0].z(), corner.z() - 0.3);
  const TemplateHead& head = test::coarse_template_head();
  const Vec3 brow = head.landmarks[static_cast<std::size_t>(find_template_landmark(head, "g'"))].skin + Vec3(20, 0, 5);
  const Vec3 on_skin = track(cached_preset("neutral"), {brow})[0];
  EXPECT_GT(track(cached_preset("surprise"), {brow})[0].z(), on_skin.z() + 0.5);
}

TEST(FaceExpression, IdenticalAtOneAndFourThreads) {
  const int before = thread_count();
  set_thread_count(1);
  const FaceExpression one = expressions().pose("frown", expression_preset("frown"));
  set_thread_count(4);
  const FaceExpression four = expressions().pose("frown", expression_preset("frown"));
  set_thread_count(before);
  ASSERT_EQ(one.skin_positions.size(), four.skin_positions.size());
  for (std::size_t i = 0; i < one.skin_positions.size(); ++i) ASSERT_EQ(one.skin_positions[i], four.skin_positions[i]);
}

/// Largest net force on a free node (max over the gradient's entries).
double max_force(const MuscleContractionSolver& solver, const std::vector<Vec3>& x, const std::vector<double>& act) {
  std::vector<double> g;
  solver.energy(x, act, &g);
  double f = 0.0;
  for (double v : g) f = std::max(f, std::abs(v));
  return f;
}

TEST(MuscleContraction, QuasiNewtonMeetsTheForceToleranceOnTheWholeHeadAfterTheRegionGrows) {
  // A 2 mm margin is far too small: the region must grow until the held nodes are in equilibrium too.
  const TemplateHead& head = test::coarse_template_head();
  const SkinMuscleModel& model = expressions().model();
  MuscleContractionOptions options;
  options.region_margin_mm = 2.0;
  const MuscleContractionSolver solver(model, options);
  const std::vector<double> act = resolve_activations(model.muscle_names, expression_preset("smile"));
  const ContractionResult r = solver.solve(act);
  const double tolerance = options.relative_force_tolerance * max_force(solver, model.node_rest_positions, act);
  EXPECT_LE(max_force(solver, r.node_positions, act), tolerance);
  EXPECT_LE(r.max_force, tolerance);
  // The same criterion as the solve with the default margin: both lie within the tolerance's reach of each
  // other (the soft, loosely held cheeks move most).
  const FaceExpression standard = cached_preset("smile");
  double difference = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    difference = std::max(difference, (r.node_positions[i] - standard.skin_positions[i]).norm());
    moved = std::max(moved, (standard.skin_positions[i] - head.skin.positions[i]).norm());
  }
  EXPECT_LT(difference, 0.5 * moved);
}

TEST(FaceExpression, MorphTargetsReadBackFromGlb) {
  const TriMesh& skin = test::coarse_template_head().skin;
  const std::vector<FaceExpression> poses = {cached_preset("smile"), cached_preset("surprise")};
  GltfMeshNode node;
  node.name = "head";
  node.mesh = skin;
  node.morph_targets = expression_morph_targets(skin, poses);
  GltfScene scene;
  scene.nodes.push_back(node);
  const auto path = test::scratch_dir("expression_glb") / "head.glb";
  write_gltf(path, scene);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path.string())) << error;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Mesh& mesh = model.meshes[0];
  ASSERT_EQ(mesh.primitives.size(), 1u);
  const tinygltf::Primitive& primitive = mesh.primitives[0];
  ASSERT_EQ(primitive.targets.size(), poses.size());
  const tinygltf::Value& names = mesh.extras.Get("targetNames");
  ASSERT_TRUE(names.IsArray());
  ASSERT_EQ(names.ArrayLen(), poses.size());
  for (std::size_t t = 0; t < poses.size(); ++t)
    EXPECT_EQ(names.Get(static_cast<int>(t)).Get<std::string>(), poses[t].name);

  auto floats = [&](int accessor_index) {
    const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(accessor_index));
    EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(a.type, TINYGLTF_TYPE_VEC3);
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    const std::size_t stride = view.byteStride == 0 ? 3 * sizeof(float) : view.byteStride;
    std::vector<Eigen::Vector3f> out(a.count);
    const unsigned char* data = model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data();
    for (std::size_t i = 0; i < a.count; ++i)
      std::memcpy(out[i].data(), data + view.byteOffset + a.byteOffset + i * stride, 3 * sizeof(float));
    return out;
  };
  // glTF vertices are the welded ones, split at UV seams: find each one's skin vertex by its position.
  const std::vector<Eigen::Vector3f> positions = floats(primitive.attributes.at("POSITION"));
  std::map<std::tuple<float, float, float>, std::size_t> by_position;
  for (std::size_t v = 0; v < skin.positions.size(); ++v) {
    const Eigen::Vector3f p = (0.001 * skin.positions[v]).cast<float>();
    by_position[{p.x(), p.y(), p.z()}] = v;
  }
  ASSERT_GE(positions.size(), skin.positions.size());
  for (std::size_t t = 0; t < poses.size(); ++t) {
    const std::vector<Eigen::Vector3f> deltas = floats(primitive.targets[t].at("POSITION"));
    ASSERT_EQ(deltas.size(), positions.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const auto it = by_position.find({positions[i].x(), positions[i].y(), positions[i].z()});
      ASSERT_NE(it, by_position.end()) << "glTF vertex " << i << " is no skin vertex";
      const Vec3 expected = 0.001 * (poses[t].skin_positions[it->second] - skin.positions[it->second]);  // m
      EXPECT_LE((deltas[i].cast<double>() - expected).norm(), 1e-7 * std::max(1.0, expected.norm()) + 1e-9)
          << poses[t].name << " vertex " << i;
      largest = std::max(largest, expected.norm());
    }
    EXPECT_GT(largest, 1e-3) << poses[t].name << " moves the skin by over 1 mm";
  }
}

TEST(FaceExpression, MorphTargetsByPresetNames) {
  const TemplateHead& head = test::coarse_template_head();
  const auto muscles = shape_muscles(head.muscles, head.skin);
  EXPECT_THROW(expression_morph_targets(head.skin, head.skull, muscles, {"smile", "smiel"}), InputError);
  EXPECT_THROW(expression_morph_targets(head.skin, head.skull, muscles, {"frown", "frown"}), InputError);
  const std::vector<MorphTarget> targets =
      expression_morph_targets(head.skin, head.skull, muscles, {"neutral", "frown"});
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_EQ(targets[0].name, "neutral");
  EXPECT_EQ(targets[1].name, "frown");
  const FaceExpression& frown = cached_preset("frown");
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    ASSERT_EQ(targets[0].position_deltas[i], Vec3::Zero());
    ASSERT_EQ(targets[1].position_deltas[i], frown.skin_positions[i] - head.skin.positions[i]);
  }
}

TEST(FaceExpression, RejectsBadActivationsAndNames) {
  const FaceExpressions& e = expressions();
  EXPECT_THROW(e.pose("x", {{"risorius_L", 1.5}}), InputError);
  EXPECT_THROW(e.pose("x", {{"risorius_L", -0.1}}), InputError);
  EXPECT_THROW(e.pose("x", {{"risorius", std::numeric_limits<double>::quiet_NaN()}}), InputError);
  try {
    e.pose("x", {{"zygomaticus_majr", 0.5}});
    ADD_FAILURE() << "no throw";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("did you mean \"zygomaticus_major\""), std::string::npos) << err.what();
  }
  try {
    expression_preset("smiel");
    ADD_FAILURE() << "no throw";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("\"smile\""), std::string::npos) << err.what();
  }
  std::vector<double> wrong(e.model().muscle_names.size(), 0.0);
  wrong[3] = 2.0;
  EXPECT_THROW(e.solver().solve(wrong), InputError);
  EXPECT_THROW(e.solver().solve({0.5}), InputError);
  MuscleContractionOptions bad_margin, bad_history;
  bad_margin.region_margin_mm = -1.0;
  bad_history.quasi_newton_history = 0;
  EXPECT_THROW(MuscleContractionSolver(e.model(), bad_margin), InputError);
  EXPECT_THROW(MuscleContractionSolver(e.model(), bad_history), InputError);
}

TEST(FaceExpression, MorphTargetsHoldDisplacementsAndNames) {
  const TriMesh& skin = test::coarse_template_head().skin;
  const std::vector<FaceExpression> poses = {cached_preset("neutral"), cached_preset("surprise")};
  const std::vector<MorphTarget> targets = expression_morph_targets(skin, poses);
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_EQ(targets[1].name, "surprise");
  double neutral_max = 0.0, surprise_max = 0.0;
  for (std::size_t i = 0; i < skin.positions.size(); ++i) {
    neutral_max = std::max(neutral_max, targets[0].position_deltas[i].norm() + targets[0].normal_deltas[i].norm());
    EXPECT_EQ(targets[1].position_deltas[i], poses[1].skin_positions[i] - skin.positions[i]);
    surprise_max = std::max(surprise_max, targets[1].position_deltas[i].norm());
  }
  EXPECT_EQ(neutral_max, 0.0);
  EXPECT_GT(surprise_max, 1.0);
  FaceExpression bad;
  bad.skin_positions.resize(3);
  EXPECT_THROW(expression_morph_targets(skin, {bad}), InputError);
}

}  // namespace
}  // namespace forensim
