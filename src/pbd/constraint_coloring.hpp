#pragma once
/// Graph colouring of constraints for parallel Gauss-Seidel projection (as in Bender's PositionBasedDynamics and
/// NVIDIA's PBD solvers): constraints of one colour share no particle, so a colour's projections can run in
/// parallel and each writes only its own particles; colours run one after another. Greedy in constraint order,
/// so the groups (and the solve) are the same on every machine and at every thread count.

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Constraint indices per colour (colour 0 first; each list ascending).
using ConstraintGroups = std::vector<std::vector<std::uint32_t>>;

/// Colours `constraint_count` constraints of `arity` particles each, stored flat in `particles`
/// (constraint c uses particles[c * arity .. c * arity + arity - 1], each in [0, particle_count)): constraint c
/// gets the smallest colour that none of its particles has yet. Throws InputError for an index out of range.
ConstraintGroups color_constraints(const Index* particles, std::size_t constraint_count, int arity,
                                   std::size_t particle_count);

/// color_constraints() of constraints stored as fixed-size index arrays (stretch pairs, bending quads).
template <std::size_t N>
ConstraintGroups color_constraints(const std::vector<std::array<Index, N>>& constraints, std::size_t particle_count) {
  return color_constraints(constraints.empty() ? nullptr : constraints.front().data(), constraints.size(),
                           static_cast<int>(N), particle_count);
}

/// Whether no two constraints of a group share a particle (for tests and checks).
bool groups_are_independent(const ConstraintGroups& groups, const Index* particles, int arity,
                            std::size_t particle_count);

/// groups_are_independent() for fixed-size index arrays.
template <std::size_t N>
bool groups_are_independent(const ConstraintGroups& groups, const std::vector<std::array<Index, N>>& constraints,
                            std::size_t particle_count) {
  return groups_are_independent(groups, constraints.empty() ? nullptr : constraints.front().data(), static_cast<int>(N),
                                particle_count);
}

}  // namespace forensim
