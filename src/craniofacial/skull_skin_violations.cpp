#include "craniofacial/skull_skin_violations.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/winding_number.hpp"

namespace forensim {

SkullSkinViolations count_skull_skin_violations(const TriMesh& skull, const TriMesh& skin) {
  require_input(!skull.triangles.empty(), "skull mesh", "", "has no triangles");
  require_input(!skin.triangles.empty(), "skin mesh", "", "has no triangles");
  skull.validate("skull mesh");
  skin.validate("skin mesh");
  SkullSkinViolations v;
  v.skull_vertex_count = skull.positions.size();
  v.skin_vertex_count = skin.positions.size();

  const WindingNumber skin_winding(skin);
  const std::vector<double> w_skin = skin_winding.evaluate_batch(skull.positions);
  std::vector<Vec3> outside;
  for (std::size_t i = 0; i < w_skin.size(); ++i) {
    if (w_skin[i] < 0.5) {
      v.skull_vertices_outside.push_back(i);
      outside.push_back(skull.positions[i]);
    }
  }
  v.skull_outside_skin = outside.size();
  if (!outside.empty()) {
    const ClosestPointQuery to_skin(skin);
    for (const auto& c : to_skin.query_batch(outside))
      v.max_skull_protrusion_mm = std::max(v.max_skull_protrusion_mm, c->distance);
  }

  const WindingNumber skull_winding(skull);
  const std::vector<double> w_skull = skull_winding.evaluate_batch(skin.positions);
  std::vector<Vec3> inside;
  for (std::size_t i = 0; i < w_skull.size(); ++i) {
    if (w_skull[i] > 0.5) {
      v.skin_vertices_inside.push_back(i);
      inside.push_back(skin.positions[i]);
    }
  }
  v.skin_inside_skull = inside.size();
  if (!inside.empty()) {
    const ClosestPointQuery to_skull(skull);
    for (const auto& c : to_skull.query_batch(inside))
      v.max_skin_intrusion_mm = std::max(v.max_skin_intrusion_mm, c->distance);
  }
  return v;
}

namespace {

/// True when the oriented edges of `triangles` cancel (each edge a->b matched by one b->a): a closed surface,
/// whose winding number is an integer away from it.
bool closed_surface(const std::vector<Tri>& triangles) {
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(3 * triangles.size());
  for (const Tri& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint64_t>(t[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::uint64_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      edges.emplace_back(a < b ? (a << 32) | b : (b << 32) | a, a < b ? 1 : -1);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    int sum = 0;
    std::size_t j = i;
    for (; j < edges.size() && edges[j].first == edges[i].first; ++j) sum += edges[j].second;
    if (sum != 0) return false;
    i = j;
  }
  return true;
}

/// Largest |coordinate| of `positions`, for a rounding margin in mm.
double coordinate_scale(const std::vector<Vec3>& positions) {
  double s = 1.0;
  for (const Vec3& p : positions) s = std::max(s, p.cwiseAbs().maxCoeff());
  return s;
}

}  // namespace

SkullSkinViolationCounter::SkullSkinViolationCounter(const TriMesh& skull) : m_skull(skull) {
  require_input(!skull.triangles.empty(), "skull mesh", "", "has no triangles");
  skull.validate("skull mesh");
}

SkullSkinViolationCounter::~SkullSkinViolationCounter() = default;

void SkullSkinViolationCounter::build() const {
  if (m_skull_winding) return;
  m_skull_winding = std::make_unique<WindingNumber>(m_skull);
  m_skull_closest = std::make_unique<ClosestPointQuery>(m_skull);
  m_skull_closed = closed_surface(m_skull.triangles);
  m_skull_edges.clear();
  for (const Tri& t : m_skull.triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(t[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::uint32_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      m_skull_edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(m_skull_edges.begin(), m_skull_edges.end());
  m_skull_edges.erase(std::unique(m_skull_edges.begin(), m_skull_edges.end()), m_skull_edges.end());
  m_skull_reach.assign(m_skull.positions.size(), 0.0);
  for (const auto& e : m_skull_edges) {
    const double length = (m_skull.positions[e[0]] - m_skull.positions[e[1]]).norm();
    m_skull_reach[e[0]] = std::max(m_skull_reach[e[0]], length);
    m_skull_reach[e[1]] = std::max(m_skull_reach[e[1]], length);
  }
  // The vertex grid: about 8 cells per vertex of the bounding box, at most 256 a side.
  const std::vector<Vec3>& p = m_skull.positions;
  Vec3 lo = p.front(), hi = p.front();
  for (const Vec3& q : p) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(1e-3));
  double cell = std::cbrt(extent.prod() / (8.0 * static_cast<double>(p.size())));
  cell = std::max({cell, extent.maxCoeff() / 256.0, 1e-3});
  m_grid_origin = lo;
  m_grid_cell_mm = cell;
  for (int k = 0; k < 3; ++k) m_grid_size[k] = std::max(1, static_cast<int>(std::ceil(extent[k] / cell)) + 1);
  const std::size_t cells = static_cast<std::size_t>(m_grid_size[0]) * static_cast<std::size_t>(m_grid_size[1]) *
                            static_cast<std::size_t>(m_grid_size[2]);
  std::vector<std::uint32_t> cell_of(p.size());
  m_grid_start.assign(cells + 1, 0);
  for (std::size_t v = 0; v < p.size(); ++v) {
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<int>((p[v][k] - lo[k]) / cell), 0, m_grid_size[k] - 1);
    cell_of[v] = static_cast<std::uint32_t>(
        (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(m_grid_size[1]) + static_cast<std::size_t>(c[1])) *
            static_cast<std::size_t>(m_grid_size[0]) +
        static_cast<std::size_t>(c[0]));
    ++m_grid_start[cell_of[v] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) m_grid_start[c + 1] += m_grid_start[c];
  m_grid_vertices.assign(p.size(), 0);
  std::vector<std::uint32_t> fill(m_grid_start.begin(), m_grid_start.end() - 1);
  for (std::size_t v = 0; v < p.size(); ++v) m_grid_vertices[fill[cell_of[v]]++] = static_cast<std::uint32_t>(v);
}

const ClosestPointQuery& SkullSkinViolationCounter::skull_closest() const {
  build();
  return *m_skull_closest;
}

bool SkullSkinViolationCounter::swept_skull_vertices(const std::vector<Vec3>& old, const std::vector<Vec3>& positions,
                                                     std::vector<std::uint32_t>& out) const {
  const double margin = 1e-6 * std::max(coordinate_scale(old), coordinate_scale(positions));
  const std::size_t n = m_skin_triangles.size();
  std::vector<double> reach(n);
  std::vector<std::array<int, 6>> boxes(n);
  double work = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    const Tri& tri = m_skin_triangles[t];
    double delta = 0.0;
    Vec3 lo = old[static_cast<std::size_t>(tri[0])], hi = lo;
    for (const Index i : tri) {
      const auto v = static_cast<std::size_t>(i);
      delta = std::max(delta, (positions[v] - old[v]).norm());
      lo = lo.cwiseMin(old[v]);
      hi = hi.cwiseMax(old[v]);
    }
    reach[t] = delta + margin;
    std::array<int, 6>& box = boxes[t];
    double cells = 1.0;
    for (int k = 0; k < 3; ++k) {
      box[static_cast<std::size_t>(k)] = std::clamp(
          static_cast<int>(std::floor((lo[k] - reach[t] - m_grid_origin[k]) / m_grid_cell_mm)), 0, m_grid_size[k] - 1);
      box[static_cast<std::size_t>(k) + 3] = std::clamp(
          static_cast<int>(std::floor((hi[k] + reach[t] - m_grid_origin[k]) / m_grid_cell_mm)), 0, m_grid_size[k] - 1);
      cells *= box[static_cast<std::size_t>(k) + 3] - box[static_cast<std::size_t>(k)] + 1;
    }
    work += cells;
  }
  // A cell visit and its few distance tests take nanoseconds, a winding-number evaluation near the skin tens of
  // microseconds: the search pays while it visits at most a few hundred cells per skull vertex.
  if (work > 512.0 * static_cast<double>(m_skull.positions.size())) return false;
  constexpr std::size_t grain = 256;
  std::vector<std::vector<std::uint32_t>> found((n + grain - 1) / grain);
  const std::vector<Vec3>& skull = m_skull.positions;
  // Fixed blocks of `grain` triangles, one list each: the chunks of parallel_for_chunks are at most `grain` long
  // but not aligned to it, so two chunks could share a list.
  parallel_for(
      0, found.size(),
      [&](std::size_t block) {
        std::vector<std::uint32_t>& mine = found[block];
        const std::size_t begin = block * grain, end = std::min(n, begin + grain);
        for (std::size_t t = begin; t < end; ++t) {
          const Tri& tri = m_skin_triangles[t];
          const Vec3& a = old[static_cast<std::size_t>(tri[0])];
          const Vec3& b = old[static_cast<std::size_t>(tri[1])];
          const Vec3& c = old[static_cast<std::size_t>(tri[2])];
          const double reach2 = reach[t] * reach[t];
          const std::array<int, 6>& box = boxes[t];
          for (int z = box[2]; z <= box[5]; ++z) {
            for (int y = box[1]; y <= box[4]; ++y) {
              const std::size_t row = (static_cast<std::size_t>(z) * static_cast<std::size_t>(m_grid_size[1]) +
                                       static_cast<std::size_t>(y)) *
                                      static_cast<std::size_t>(m_grid_size[0]);
              for (std::uint32_t k = m_grid_start[row + static_cast<std::size_t>(box[0])];
                   k < m_grid_start[row + static_cast<std::size_t>(box[3]) + 1]; ++k) {
                const std::uint32_t v = m_grid_vertices[k];
                const Vec3& q = skull[v];
                const Vec3 w = closest_point_on_triangle(q, a, b, c);
                if ((w[0] * a + w[1] * b + w[2] * c - q).squaredNorm() <= reach2) mine.push_back(v);
              }
            }
          }
        }
      },
      1);
  out.clear();
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return true;
}

std::size_t SkullSkinViolationCounter::grouped_sides(const WindingNumber& winding, const ClosestPointQuery& closest,
                                                     std::vector<char>& outside) const {
  const std::vector<Vec3>& p = m_skull.positions;
  const std::size_t n = p.size();
  const double margin = 1e-6 * coordinate_scale(p);
  // Free vertices: no skin point within their longest edge (and a rounding margin).
  std::vector<char> free(n, 0);
  parallel_for(
      0, n, [&](std::size_t v) { free[v] = closest.query(p[v], m_skull_reach[v] * (1.0 + 1e-9) + margin) ? 0 : 1; },
      256);
  // Union-find over the edges at free vertices; each group's side is its lowest vertex's.
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) {
      parent[v] = parent[parent[v]];
      v = parent[v];
    }
    return v;
  };
  for (const auto& e : m_skull_edges) {
    if (!free[e[0]] && !free[e[1]]) continue;
    const std::uint32_t a = find(e[0]), b = find(e[1]);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::uint32_t> roots;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (find(v) == v) roots.push_back(v);
  }
  std::vector<Vec3> points(roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) points[i] = p[roots[i]];
  const std::vector<double> w = winding.evaluate_batch(points);
  std::vector<char> root_outside(n, 0);
  for (std::size_t i = 0; i < roots.size(); ++i) root_outside[roots[i]] = w[i] < 0.5 ? 1 : 0;
  outside.assign(n, 0);
  for (std::uint32_t v = 0; v < n; ++v) outside[v] = root_outside[find(v)];
  return roots.size();
}

SkullSkinViolations SkullSkinViolationCounter::count(const TriMesh& skin) {
  require_input(!skin.triangles.empty(), "skin mesh", "", "has no triangles");
  skin.validate("skin mesh");
  build();
  const std::size_t n_skull = m_skull.positions.size();
  const std::size_t n_skin = skin.positions.size();
  if (m_counted.empty() || skin.triangles != m_skin_triangles || n_skin != m_counted.front().skin_positions.size()) {
    m_counted.clear();
    m_skin_triangles = skin.triangles;
    m_skin_closed = closed_surface(skin.triangles);
  }
  // The remembered skin whose vertices moved least.
  std::size_t nearest = m_counted.size();
  double nearest_move = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < m_counted.size(); ++s) {
    double move = 0.0;
    for (std::size_t i = 0; i < n_skin; ++i)
      move = std::max(move, (skin.positions[i] - m_counted[s].skin_positions[i]).squaredNorm());
    if (move < nearest_move) {
      nearest_move = move;
      nearest = s;
    }
  }
  m_last_evaluated = 0;
  Counted now;
  std::unique_ptr<ClosestPointQuery> skin_closest;
  if (nearest < m_counted.size() && nearest_move == 0.0) {
    now = m_counted[nearest];  // the same skin again
  } else {
    const Counted* from = nearest < m_counted.size() ? &m_counted[nearest] : nullptr;
    const WindingNumber skin_winding(skin);
    // Skull vertices against the skin.
    std::vector<std::uint32_t> candidates;
    if (from && m_skin_closed && swept_skull_vertices(from->skin_positions, skin.positions, candidates)) {
      now.skull_outside = from->skull_outside;
      std::vector<Vec3> points(candidates.size());
      for (std::size_t i = 0; i < candidates.size(); ++i) points[i] = m_skull.positions[candidates[i]];
      const std::vector<double> w = skin_winding.evaluate_batch(points);
      for (std::size_t i = 0; i < candidates.size(); ++i) now.skull_outside[candidates[i]] = w[i] < 0.5 ? 1 : 0;
      m_last_evaluated += candidates.size();
    } else if (m_skin_closed) {
      skin_closest = std::make_unique<ClosestPointQuery>(skin);
      m_last_evaluated += grouped_sides(skin_winding, *skin_closest, now.skull_outside);
    } else {
      const std::vector<double> w = skin_winding.evaluate_batch(m_skull.positions);
      now.skull_outside.assign(n_skull, 0);
      for (std::size_t i = 0; i < n_skull; ++i) now.skull_outside[i] = w[i] < 0.5 ? 1 : 0;
      m_last_evaluated += n_skull;
    }
    // Skin vertices against the skull.
    if (from && m_skull_closed) {
      const std::vector<Vec3>& old = from->skin_positions;
      const double margin = 1e-6 * std::max(coordinate_scale(old), coordinate_scale(skin.positions));
      std::vector<char> again(n_skin, 0);
      parallel_for(
          0, n_skin,
          [&](std::size_t i) {
            const double delta = (skin.positions[i] - old[i]).norm();
            if (delta > 0.0) again[i] = m_skull_closest->query(old[i], delta + margin) ? 1 : 0;
          },
          64);
      std::vector<std::size_t> which;
      std::vector<Vec3> points;
      for (std::size_t i = 0; i < n_skin; ++i) {
        if (!again[i]) continue;
        which.push_back(i);
        points.push_back(skin.positions[i]);
      }
      now.skin_inside = from->skin_inside;
      const std::vector<double> w = m_skull_winding->evaluate_batch(points);
      for (std::size_t k = 0; k < which.size(); ++k) now.skin_inside[which[k]] = w[k] > 0.5 ? 1 : 0;
      m_last_evaluated += which.size();
    } else {
      const std::vector<double> w = m_skull_winding->evaluate_batch(skin.positions);
      now.skin_inside.assign(n_skin, 0);
      for (std::size_t i = 0; i < n_skin; ++i) now.skin_inside[i] = w[i] > 0.5 ? 1 : 0;
      m_last_evaluated += n_skin;
    }
    now.skin_positions = skin.positions;
  }
  constexpr std::size_t kept = 3;
  if (nearest < m_counted.size() && nearest_move == 0.0)
    m_counted.erase(m_counted.begin() + static_cast<std::ptrdiff_t>(nearest));
  m_counted.insert(m_counted.begin(), now);
  if (m_counted.size() > kept) m_counted.resize(kept);
  const std::vector<char>& skull_outside = m_counted.front().skull_outside;
  const std::vector<char>& skin_inside = m_counted.front().skin_inside;

  SkullSkinViolations v;
  v.skull_vertex_count = n_skull;
  v.skin_vertex_count = n_skin;
  std::vector<Vec3> outside, inside;
  for (std::size_t i = 0; i < n_skull; ++i) {
    if (!skull_outside[i]) continue;
    v.skull_vertices_outside.push_back(i);
    outside.push_back(m_skull.positions[i]);
  }
  for (std::size_t i = 0; i < n_skin; ++i) {
    if (!skin_inside[i]) continue;
    v.skin_vertices_inside.push_back(i);
    inside.push_back(skin.positions[i]);
  }
  v.skull_outside_skin = outside.size();
  v.skin_inside_skull = inside.size();
  if (!outside.empty()) {
    if (!skin_closest) skin_closest = std::make_unique<ClosestPointQuery>(skin);
    for (const auto& c : skin_closest->query_batch(outside))
      v.max_skull_protrusion_mm = std::max(v.max_skull_protrusion_mm, c->distance);
  }
  if (!inside.empty()) {
    for (const auto& c : m_skull_closest->query_batch(inside))
      v.max_skin_intrusion_mm = std::max(v.max_skin_intrusion_mm, c->distance);
  }
  return v;
}

}  // namespace forensim
