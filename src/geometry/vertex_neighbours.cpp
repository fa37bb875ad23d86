#include "geometry/vertex_neighbours.hpp"

#include "core/error.hpp"
#include "geometry/mesh_topology.hpp"

namespace forensim {

VertexNeighbours vertex_neighbours(const std::vector<Tri>& triangles, std::size_t vertex_count) {
  bool inside = true;
  for (const Tri& t : triangles)
    for (const Index i : t) inside = inside && i >= 0 && std::size_t(i) < vertex_count;
  require_input(inside, "vertex_neighbours", "triangles", "hold a vertex index outside the mesh");
  const std::vector<std::array<Index, 2>> edges = unique_edges(triangles);
  VertexNeighbours out;
  out.start.assign(vertex_count + 1, 0);
  for (const auto& e : edges) {
    ++out.start[std::size_t(e[0]) + 1];
    ++out.start[std::size_t(e[1]) + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) out.start[v + 1] += out.start[v];
  out.index.resize(out.start[vertex_count]);
  std::vector<std::size_t> fill(out.start.begin(), out.start.end() - 1);
  for (const auto& e : edges) {
    out.index[fill[std::size_t(e[0])]++] = e[1];
    out.index[fill[std::size_t(e[1])]++] = e[0];
  }
  return out;
}

}  // namespace forensim
