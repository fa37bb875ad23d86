#pragma once
/// Splitting a welded mesh at UV seams, for formats whose texture coordinates are per vertex (PLY, glTF).
/// forensim meshes index UVs per triangle corner; these formats need one vertex per distinct
/// (position, uv) pair.

#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// A welded mesh re-indexed with one vertex per distinct (vertex, uv) pair.
struct SeamSplitMesh {
  std::vector<Index> source_vertex;  ///< #V' welded vertex that each split vertex copies (position, normal,
                                     ///< colour, morph deltas)
  std::vector<Vec2> uvs;             ///< #V' per-vertex texture coordinate; empty when the mesh has no UVs
  std::vector<Tri> triangles;        ///< #F triangles indexing the split vertices, same order as the mesh's
};

/// Splits `mesh` at its UV seams. Without UVs the result is the identity map (V' = V). Split vertices are
/// numbered in order of first use by the triangles, then unreferenced vertices follow (so none is lost).
SeamSplitMesh split_uv_seams(const TriMesh& mesh);

}  // namespace forensim
