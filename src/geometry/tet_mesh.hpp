#pragma once
/// Tetrahedral volume mesh: the body model of the desiccation system. Each tet carries a region label
/// (flesh, bone, ...). Lengths are millimetres.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/field_set.hpp"

namespace forensim {

/// Region labels of body-model tets.
enum TissueLabel : int {
  tissue_flesh = 0,  ///< soft tissue: holds water, shrinks
  tissue_bone = 1,   ///< bone: holds no water, rigid
};

struct TetMesh {
  std::vector<Vec3> positions;  ///< #V node positions
  std::vector<Tet> tets;        ///< #T tets, positively oriented: (p1-p0).dot((p2-p0).cross(p3-p0)) > 0
  std::vector<int> tet_labels;  ///< #T region labels (TissueLabel), or empty (all flesh)
  FieldSet vertex_fields;       ///< named per-node data
  FieldSet tet_fields;          ///< named per-tet data

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t tet_count() const { return tets.size(); }
  int label(std::size_t tet) const { return tet_labels.empty() ? tissue_flesh : tet_labels[tet]; }

  /// Checks index ranges, finiteness and array sizes. Throws InputError naming `source` and the element.
  void validate(const std::string& source) const;
};

}  // namespace forensim
