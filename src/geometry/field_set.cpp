#include "geometry/field_set.hpp"

#include <cmath>

#include "core/error.hpp"

namespace forensim {

void FieldSet::validate(std::size_t count, const std::string& source, const std::string& element_kind) const {
  for (const auto& [name, values] : scalars) {
    require_input(values.size() == count, source, "field '" + name + "'",
                  "has " + std::to_string(values.size()) + " values for " + std::to_string(count) + " " + element_kind);
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (std::isnan(values[i]))
        throw InputError(source, "field '" + name + "'", "value " + std::to_string(i) + " is NaN");
    }
  }
  for (const auto& [name, values] : vectors) {
    require_input(
        values.size() == count, source, "field '" + name + "'",
        "has " + std::to_string(values.size()) + " vectors for " + std::to_string(count) + " " + element_kind);
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (values[i].hasNaN())
        throw InputError(source, "field '" + name + "'", "vector " + std::to_string(i) + " has NaN");
    }
  }
}

}  // namespace forensim
