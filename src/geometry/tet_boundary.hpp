#pragma once
/// Boundary faces of a tetrahedral mesh, each with the tet and local face it comes from, and the
/// interfaces between labelled regions (flesh/bone).

#include <vector>

#include "core/types.hpp"
#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Local faces of a tet, ordered so that they face outward for a positively oriented tet. Face f is
/// opposite local node f.
inline constexpr int tet_local_faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// A triangle of the boundary (or of a region interface) and where it comes from.
struct TetFace {
  Tri vertices;    ///< node indices, counter-clockwise seen from outside the tet
  Index tet;       ///< the tet it belongs to
  int local_face;  ///< 0..3, the face opposite that local node
};

/// Faces used by exactly one tet. With `label` >= 0, the boundary of the region of tets with that label
/// (faces whose other tet is absent or labelled differently).
std::vector<TetFace> tet_boundary_faces(const TetMesh& mesh, int label = -1);

/// The boundary as a triangle mesh over a compacted vertex set. `face_source` receives each triangle's
/// TetFace and `node_of_vertex` each surface vertex's tet-mesh node, when not null.
TriMesh tet_boundary_mesh(const TetMesh& mesh, int label = -1, std::vector<TetFace>* face_source = nullptr,
                          std::vector<Index>* node_of_vertex = nullptr);

/// For each tet, the four neighbouring tets across its local faces (-1 on the boundary).
std::vector<std::array<Index, 4>> tet_neighbors(const TetMesh& mesh);

}  // namespace forensim
