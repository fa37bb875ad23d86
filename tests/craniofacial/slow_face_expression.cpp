// The quasi-Newton expression solver against the projected-Newton reference (one Cholesky refactorisation per
// step, seconds per expression): both, converged tightly, reach the same equilibrium.
#include <gtest/gtest.h>

#include <algorithm>

#include "craniofacial/face_expression.hpp"
#include "template_head_fixture.hpp"

namespace forensim {
namespace {

TEST(MuscleContraction, QuasiNewtonAndNewtonReachTheSameEquilibrium) {
  const TemplateHead& head = test::coarse_template_head();
  const auto muscles = shape_muscles(head.muscles, head.skin);
  MuscleContractionOptions quasi_newton, newton;
  quasi_newton.relative_force_tolerance = newton.relative_force_tolerance = 1e-6;
  quasi_newton.max_quasi_newton_iterations = 20000;
  newton.method = ContractionMethod::newton;
  newton.max_newton_iterations = 400;
  const FaceExpressions a(head.skin, head.skull, muscles, {}, quasi_newton);
  const FaceExpressions b(head.skin, head.skull, muscles, {}, newton);
  const MuscleActivations pose = {{"zygomaticus_major_L", 0.6}, {"frontalis", 0.5}};
  const FaceExpression ea = a.pose("p", pose), eb = b.pose("p", pose);
  double difference = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    difference = std::max(difference, (ea.skin_positions[i] - eb.skin_positions[i]).norm());
    moved = std::max(moved, (eb.skin_positions[i] - head.skin.positions[i]).norm());
  }
  EXPECT_GT(moved, 1.0);
  EXPECT_LT(difference, 0.01 * moved) << "quasi-Newton " << ea.newton_iterations << " iterations, Newton "
                                      << eb.newton_iterations;
}

}  // namespace
}  // namespace forensim
