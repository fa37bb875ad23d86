// The quasi-Newton expression solver against the projected-Newton reference (one Cholesky refactorisation per
// step, seconds per expression), both converged tightly on the coarse template head.
#include <gtest/gtest.h>

#include <algorithm>

#include "craniofacial/face_expression.hpp"
#include "template_head_fixture.hpp"

namespace forensim {
namespace {

struct Pair {
  ContractionResult quasi_newton, newton;
  double difference_mm = 0.0;                                   ///< largest distance between a node of the two
  double moved_mm = 0.0;                                        ///< largest displacement of a node in the Newton result
  double tolerance = 0.0;                                       ///< the force tolerance both met
  double max_force_quasi_newton = 0.0, max_force_newton = 0.0;  ///< recomputed from energy()
};

Pair solve_both(const MuscleActivations& pose) {
  const TemplateHead& head = test::coarse_template_head();
  static const auto muscles = shape_muscles(head.muscles, head.skin);
  static const SkinMuscleModel model = make_skin_muscle_model(head.skin, head.skull, muscles);
  MuscleContractionOptions q, n;
  q.relative_force_tolerance = n.relative_force_tolerance = 1e-6;
  q.max_quasi_newton_iterations = 20000;
  n.method = ContractionMethod::newton;
  n.max_newton_iterations = 400;
  const MuscleContractionSolver a(model, q), b(model, n);
  const std::vector<double> act = resolve_activations(model.muscle_names, pose);
  Pair p;
  p.quasi_newton = a.solve(act);
  p.newton = b.solve(act);
  auto max_force = [&](const std::vector<Vec3>& x) {
    std::vector<double> g;
    a.energy(x, act, &g);
    double f = 0.0;
    for (double v : g) f = std::max(f, std::abs(v));
    return f;
  };
  p.tolerance = q.relative_force_tolerance * max_force(model.node_rest_positions);
  p.max_force_quasi_newton = max_force(p.quasi_newton.node_positions);
  p.max_force_newton = max_force(p.newton.node_positions);
  for (std::size_t i = 0; i < model.node_rest_positions.size(); ++i) {
    p.difference_mm = std::max(p.difference_mm, (p.quasi_newton.node_positions[i] - p.newton.node_positions[i]).norm());
    p.moved_mm = std::max(p.moved_mm, (p.newton.node_positions[i] - model.node_rest_positions[i]).norm());
  }
  return p;
}

TEST(MuscleContraction, QuasiNewtonAndNewtonReachTheSameEquilibriumWhereItIsUnique) {
  // A gentle contraction compresses the skin too little to buckle it: one equilibrium, which both reach.
  const Pair p = solve_both({{"frontalis", 0.2}});
  EXPECT_LE(p.max_force_quasi_newton, p.tolerance);
  EXPECT_LE(p.max_force_newton, p.tolerance);
  EXPECT_GT(p.moved_mm, 0.3);
  EXPECT_LT(p.difference_mm, 0.01 * p.moved_mm) << "energies " << p.quasi_newton.energy << " " << p.newton.energy;
}

TEST(MuscleContraction, QuasiNewtonReachesAnEquilibriumAsLowAsNewtons) {
  // Strong contractions fold the compressed skin at the mouth corner, and the energy has several minima; the
  // quasi-Newton one is no higher than Newton's.
  const Pair p = solve_both({{"zygomaticus_major_L", 0.6}, {"frontalis", 0.5}});
  EXPECT_LE(p.max_force_quasi_newton, p.tolerance);
  EXPECT_LE(p.max_force_newton, p.tolerance);
  EXPECT_LE(p.quasi_newton.energy, p.newton.energy * (1.0 + 1e-9))
      << "difference " << p.difference_mm << " mm of " << p.moved_mm << " mm";
}

}  // namespace
}  // namespace forensim
