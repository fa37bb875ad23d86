#include "geometry/mesh_topology.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_map>

#include "geometry/mesh_measures.hpp"

namespace forensim {
namespace {

struct HalfEdge {
  Index a, b;  // directed a -> b
  Index tri;
};

// Union-find over indices.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

std::vector<HalfEdge> sorted_half_edges(const std::vector<Tri>& triangles) {
  std::vector<HalfEdge> edges;
  edges.reserve(triangles.size() * 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Tri& t = triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (int c = 0; c < 3; ++c) edges.push_back({t[c], t[(c + 1) % 3], static_cast<Index>(f)});
  }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    const auto kx = std::minmax(x.a, x.b), ky = std::minmax(y.a, y.b);
    return kx != ky ? kx < ky : x.tri < y.tri;
  });
  return edges;
}

}  // namespace

std::string TopologyReport::summary() const {
  std::string s = is_closed() ? "closed"
                              : "open (" + std::to_string(boundary_loop_count) + " holes, " +
                                    std::to_string(boundary_edge_count) + " boundary edges)";
  s += is_manifold() ? ", manifold"
                     : ", non-manifold (" + std::to_string(nonmanifold_edge_count) + " edges, " +
                           std::to_string(nonmanifold_vertex_count) + " vertices)";
  s += is_oriented() ? ", oriented" : ", inconsistently oriented";
  s += "; " + std::to_string(component_count) + (component_count == 1 ? " component" : " components");
  if (degenerate_triangle_count) s += "; " + std::to_string(degenerate_triangle_count) + " degenerate triangles";
  return s;
}

std::vector<std::array<Index, 2>> unique_edges(const std::vector<Tri>& triangles) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(triangles.size() * 3);
  for (const Tri& t : triangles) {
    for (int c = 0; c < 3; ++c) {
      const Index a = t[c], b = t[(c + 1) % 3];
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

TopologyReport check_topology(const TriMesh& mesh) {
  TopologyReport r;
  const std::size_t nv = mesh.positions.size();
  std::vector<char> used(nv, 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    for (Index i : t) used[i] = 1;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]) == 0.0) {
      ++r.degenerate_triangle_count;
    }
  }
  r.isolated_vertex_count = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));

  const std::vector<HalfEdge> edges = sorted_half_edges(mesh.triangles);
  DisjointSets tri_sets(mesh.triangles.size());
  DisjointSets boundary_sets(nv);
  std::vector<char> on_boundary(nv, 0);
  for (std::size_t i = 0; i < edges.size();) {
    const auto key = std::minmax(edges[i].a, edges[i].b);
    std::size_t j = i + 1;
    while (j < edges.size() && std::minmax(edges[j].a, edges[j].b) == key) {
      tri_sets.unite(edges[i].tri, edges[j].tri);
      ++j;
    }
    const std::size_t uses = j - i;
    ++r.edge_count;
    if (uses == 1) {
      ++r.boundary_edge_count;
      boundary_sets.unite(edges[i].a, edges[i].b);
      on_boundary[edges[i].a] = on_boundary[edges[i].b] = 1;
    } else if (uses == 2) {
      if (edges[i].a == edges[i + 1].a) ++r.misoriented_edge_count;
    } else {
      ++r.nonmanifold_edge_count;
    }
    i = j;
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (tri_sets.find(static_cast<int>(f)) == static_cast<int>(f)) ++r.component_count;
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (on_boundary[v] && boundary_sets.find(static_cast<int>(v)) == static_cast<int>(v)) ++r.boundary_loop_count;
  }

  // Vertex fans: the triangles around a manifold vertex form one chain connected through shared edges.
  std::vector<std::vector<Index>> vertex_tris(nv);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (Index i : t) vertex_tris[i].push_back(static_cast<Index>(f));
  }
  for (std::size_t v = 0; v < nv; ++v) {
    const auto& fan = vertex_tris[v];
    if (fan.size() < 2) continue;
    // Connect fan triangles that share the other endpoint of an edge from v.
    std::map<Index, std::vector<int>> by_neighbour;
    for (std::size_t k = 0; k < fan.size(); ++k) {
      for (Index u : mesh.triangles[fan[k]]) {
        if (u != static_cast<Index>(v)) by_neighbour[u].push_back(static_cast<int>(k));
      }
    }
    DisjointSets fan_sets(fan.size());
    for (const auto& [u, ks] : by_neighbour) {
      for (std::size_t k = 1; k < ks.size(); ++k) fan_sets.unite(ks[0], ks[k]);
    }
    for (std::size_t k = 1; k < fan.size(); ++k) {
      if (fan_sets.find(static_cast<int>(k)) != 0) {
        ++r.nonmanifold_vertex_count;
        break;
      }
    }
  }
  return r;
}

std::vector<int> triangle_components(const TriMesh& mesh, int* count) {
  DisjointSets sets(mesh.triangles.size());
  const std::vector<HalfEdge> edges = sorted_half_edges(mesh.triangles);
  for (std::size_t i = 0; i < edges.size();) {
    const auto key = std::minmax(edges[i].a, edges[i].b);
    std::size_t j = i + 1;
    while (j < edges.size() && std::minmax(edges[j].a, edges[j].b) == key) {
      sets.unite(edges[i].tri, edges[j].tri);
      ++j;
    }
    i = j;
  }
  std::vector<int> component(mesh.triangles.size(), -1);
  std::unordered_map<int, int> ids;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const int root = sets.find(static_cast<int>(f));
    auto [it, inserted] = ids.emplace(root, static_cast<int>(ids.size()));
    component[f] = it->second;
  }
  if (count) *count = static_cast<int>(ids.size());
  return component;
}

TriMesh extract_triangles(const TriMesh& mesh, const std::vector<bool>& keep_triangle) {
  TriMesh out;
  out.material = mesh.material;
  std::vector<Index> vmap(mesh.positions.size(), -1), uvmap(mesh.uvs.size(), -1);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!keep_triangle[f]) continue;
    Tri t = mesh.triangles[f];
    for (Index& i : t) {
      if (vmap[i] < 0) {
        vmap[i] = static_cast<Index>(out.positions.size());
        out.positions.push_back(mesh.positions[i]);
        if (mesh.has_normals()) out.normals.push_back(mesh.normals[i]);
        if (mesh.has_colors()) out.colors.push_back(mesh.colors[i]);
      }
      i = vmap[i];
    }
    out.triangles.push_back(t);
    if (mesh.has_uvs()) {
      Tri tu = mesh.triangle_uvs[f];
      for (Index& i : tu) {
        if (uvmap[i] < 0) {
          uvmap[i] = static_cast<Index>(out.uvs.size());
          out.uvs.push_back(mesh.uvs[i]);
        }
        i = uvmap[i];
      }
      out.triangle_uvs.push_back(tu);
    }
    if (!mesh.triangle_labels.empty()) out.triangle_labels.push_back(mesh.triangle_labels[f]);
    for (const auto& [name, values] : mesh.triangle_fields.scalars)
      out.triangle_fields.scalars[name].push_back(values[f]);
    for (const auto& [name, values] : mesh.triangle_fields.vectors)
      out.triangle_fields.vectors[name].push_back(values[f]);
  }
  for (const auto& [name, values] : mesh.vertex_fields.scalars) {
    auto& dst = out.vertex_fields.scalars[name];
    dst.resize(out.positions.size());
    for (std::size_t v = 0; v < vmap.size(); ++v) {
      if (vmap[v] >= 0) dst[vmap[v]] = values[v];
    }
  }
  for (const auto& [name, values] : mesh.vertex_fields.vectors) {
    auto& dst = out.vertex_fields.vectors[name];
    dst.resize(out.positions.size());
    for (std::size_t v = 0; v < vmap.size(); ++v) {
      if (vmap[v] >= 0) dst[vmap[v]] = values[v];
    }
  }
  return out;
}

TriMesh keep_largest_components(const TriMesh& mesh, int keep) {
  int count = 0;
  const std::vector<int> component = triangle_components(mesh, &count);
  if (count <= keep) return mesh;
  std::vector<double> area(static_cast<std::size_t>(count), 0.0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    area[component[f]] += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  }
  std::vector<int> order(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });
  std::vector<char> kept(static_cast<std::size_t>(count), 0);
  for (int k = 0; k < keep && k < count; ++k) kept[order[k]] = 1;
  std::vector<bool> mask(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) mask[f] = kept[component[f]] != 0;
  return extract_triangles(mesh, mask);
}

TriMesh weld_vertices(const TriMesh& mesh, double tolerance, std::vector<Index>* remap) {
  const std::size_t nv = mesh.positions.size();
  std::vector<Index> map(nv);
  if (tolerance <= 0) {
    // Exact duplicates only.
    std::map<std::array<double, 3>, Index> seen;
    for (std::size_t v = 0; v < nv; ++v) {
      const auto key = std::array<double, 3>{mesh.positions[v].x(), mesh.positions[v].y(), mesh.positions[v].z()};
      auto [it, inserted] = seen.emplace(key, static_cast<Index>(v));
      map[v] = it->second;
    }
  } else {
    // Hash grid of cell size `tolerance`; compare against the 27 neighbouring cells.
    struct KeyHash {
      std::size_t operator()(const std::array<long long, 3>& k) const {
        return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
      }
    };
    std::unordered_map<std::array<long long, 3>, std::vector<Index>, KeyHash> grid;
    const double tol2 = tolerance * tolerance;
    for (std::size_t v = 0; v < nv; ++v) {
      const Vec3& p = mesh.positions[v];
      const std::array<long long, 3> cell{static_cast<long long>(std::floor(p.x() / tolerance)),
                                          static_cast<long long>(std::floor(p.y() / tolerance)),
                                          static_cast<long long>(std::floor(p.z() / tolerance))};
      Index found = -1;
      for (long long dx = -1; dx <= 1 && found < 0; ++dx) {
        for (long long dy = -1; dy <= 1 && found < 0; ++dy) {
          for (long long dz = -1; dz <= 1 && found < 0; ++dz) {
            auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
            if (it == grid.end()) continue;
            for (Index u : it->second) {
              if ((mesh.positions[u] - p).squaredNorm() <= tol2) {
                found = u;
                break;
              }
            }
          }
        }
      }
      if (found >= 0) {
        map[v] = found;
      } else {
        map[v] = static_cast<Index>(v);
        grid[cell].push_back(static_cast<Index>(v));
      }
    }
  }
  TriMesh welded = mesh;
  std::vector<bool> keep(mesh.triangles.size(), true);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    Tri& t = welded.triangles[f];
    for (Index& i : t) i = map[i];
    keep[f] = t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
  }
  TriMesh out = extract_triangles(welded, keep);
  if (remap) {
    // extract_triangles renumbers in order of first use; rebuild the composite map.
    std::vector<Index> first_use(nv, -1);
    Index next = 0;
    for (std::size_t f = 0; f < welded.triangles.size(); ++f) {
      if (!keep[f]) continue;
      for (Index i : welded.triangles[f]) {
        if (first_use[i] < 0) first_use[i] = next++;
      }
    }
    remap->assign(nv, -1);
    for (std::size_t v = 0; v < nv; ++v) (*remap)[v] = first_use[map[v]];
  }
  return out;
}

}  // namespace forensim
