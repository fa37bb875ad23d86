#pragma once
/// The edge neighbours of every vertex of a triangle mesh, in compressed form: what Laplacian smoothing and
/// harmonic extensions over a mesh iterate on.

#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace forensim {

struct VertexNeighbours {
  std::vector<std::size_t> start;  ///< #V + 1: the neighbours of v are index[start[v] .. start[v + 1])
  std::vector<Index> index;        ///< neighbour vertex indices (each unique edge twice)
  std::size_t degree(std::size_t v) const { return start[v + 1] - start[v]; }
};

/// The neighbours of `vertex_count` vertices over the unique edges of `triangles` (unique_edges order: for each
/// edge (a, b), a < b, sorted, b joins a's list and a joins b's), deterministic. Vertices on no triangle have none.
/// An index outside [0, vertex_count) is refused (InputError).
VertexNeighbours vertex_neighbours(const std::vector<Tri>& triangles, std::size_t vertex_count);

}  // namespace forensim
