#include "pbd/constraint_coloring.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace forensim {

ConstraintGroups color_constraints(const Index* particles, std::size_t constraint_count, int arity,
                                   std::size_t particle_count) {
  require_input(arity > 0, "constraint colouring", "arity", "must be positive");
  // Colours already taken at each particle (few: a particle's constraint count bounds them).
  std::vector<std::vector<std::uint32_t>> taken(particle_count);
  ConstraintGroups groups;
  std::vector<std::uint32_t> used;
  for (std::size_t c = 0; c < constraint_count; ++c) {
    used.clear();
    for (int k = 0; k < arity; ++k) {
      const Index p = particles[c * static_cast<std::size_t>(arity) + static_cast<std::size_t>(k)];
      require_input(p >= 0 && static_cast<std::size_t>(p) < particle_count, "constraint colouring",
                    "constraint " + std::to_string(c), "has a particle index out of range");
      const auto& t = taken[static_cast<std::size_t>(p)];
      used.insert(used.end(), t.begin(), t.end());
    }
    std::sort(used.begin(), used.end());
    std::uint32_t colour = 0;
    for (std::uint32_t u : used) {
      if (u == colour)
        ++colour;
      else if (u > colour)
        break;
    }
    if (colour >= groups.size()) groups.resize(colour + 1);
    groups[colour].push_back(static_cast<std::uint32_t>(c));
    for (int k = 0; k < arity; ++k)
      taken[static_cast<std::size_t>(particles[c * static_cast<std::size_t>(arity) + static_cast<std::size_t>(k)])]
          .push_back(colour);
  }
  return groups;
}

bool groups_are_independent(const ConstraintGroups& groups, const Index* particles, int arity,
                            std::size_t particle_count) {
  std::vector<std::int64_t> owner(particle_count, -1);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::uint32_t c : groups[g]) {
      for (int k = 0; k < arity; ++k) {
        const auto p =
            static_cast<std::size_t>(particles[c * static_cast<std::size_t>(arity) + static_cast<std::size_t>(k)]);
        if (owner[p] == static_cast<std::int64_t>(g)) return false;
        owner[p] = static_cast<std::int64_t>(g);
      }
    }
  }
  return true;
}

}  // namespace forensim
