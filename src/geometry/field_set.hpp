#pragma once
/// Named per-element fields (scalars and 3-vectors) attached to one kind of mesh element (vertices,
/// triangles or tets): moisture, displacement, labels as numbers, quality. Every field has exactly one
/// value per element.

#include <map>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace forensim {

struct FieldSet {
  std::map<std::string, std::vector<double>> scalars;  ///< name -> one value per element
  std::map<std::string, std::vector<Vec3>> vectors;    ///< name -> one 3-vector per element

  bool empty() const { return scalars.empty() && vectors.empty(); }
  /// Throws InputError naming `source` and the field if a field does not have `count` values or holds NaN.
  void validate(std::size_t count, const std::string& source, const std::string& element_kind) const;
};

}  // namespace forensim
