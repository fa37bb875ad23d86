#include "mesh_processing/uv_atlas.hpp"

#define CGAL_EIGEN3_ENABLED 1

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // false positives inside CGAL's containers
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#pragma GCC diagnostic pop

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <unordered_map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {
namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using SurfaceMesh = cgal::SurfaceMesh;
using Point2 = cgal::Kernel::Point_2;

const char* const source = "UV atlas";

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Per-triangle Jacobian terms of Sander et al. 2001: a = Ss.Ss, b = Ss.St, c = St.St for the map from UV
/// (s, t) to the surface; returns false for a zero-area UV triangle.
bool stretch_terms(const Vec3& q1, const Vec3& q2, const Vec3& q3, const Vec2& p1, const Vec2& p2, const Vec2& p3,
                   double& a, double& b, double& c, double& uv_area) {
  const double area2 = (p2.x() - p1.x()) * (p3.y() - p1.y()) - (p3.x() - p1.x()) * (p2.y() - p1.y());
  uv_area = 0.5 * area2;
  if (!(area2 > 0.0)) return false;
  const Vec3 ss = (q1 * (p2.y() - p3.y()) + q2 * (p3.y() - p1.y()) + q3 * (p1.y() - p2.y())) / area2;
  const Vec3 st = (q1 * (p3.x() - p2.x()) + q2 * (p1.x() - p3.x()) + q3 * (p2.x() - p1.x())) / area2;
  a = ss.dot(ss);
  b = ss.dot(st);
  c = st.dot(st);
  return true;
}

/// Stretch statistics of triangles given per-corner UVs, with the UVs scaled so their area equals the
/// surface area.
struct StretchSums {
  double l2 = 1.0, max_stretch = 1.0, area_distortion = 1.0;
  std::size_t flipped = 0;
};

StretchSums measure_stretch(const std::vector<std::array<Vec3, 3>>& surface,
                            const std::vector<std::array<Vec2, 3>>& uv) {
  double area3 = 0.0, area_uv = 0.0;
  std::vector<double> tri_area3(surface.size()), tri_area_uv(surface.size());
  for (std::size_t t = 0; t < surface.size(); ++t) {
    tri_area3[t] = triangle_area(surface[t][0], surface[t][1], surface[t][2]);
    tri_area_uv[t] = 0.5 * cross2(uv[t][1] - uv[t][0], uv[t][2] - uv[t][0]);
    area3 += tri_area3[t];
    area_uv += std::max(tri_area_uv[t], 0.0);
  }
  StretchSums out;
  if (!(area3 > 0.0) || !(area_uv > 0.0)) {
    out.l2 = out.max_stretch = out.area_distortion = std::numeric_limits<double>::infinity();
    out.flipped = surface.size();
    return out;
  }
  const double norm = area_uv / area3;  // multiplies squared stretch
  double sum_l2 = 0.0, sum_distortion = 0.0, max_stretch = 0.0;
  for (std::size_t t = 0; t < surface.size(); ++t) {
    double a = 0, b = 0, c = 0, uv_area = 0;
    if (!stretch_terms(surface[t][0], surface[t][1], surface[t][2], uv[t][0], uv[t][1], uv[t][2], a, b, c, uv_area)) {
      ++out.flipped;
      sum_l2 = std::numeric_limits<double>::infinity();
      max_stretch = std::numeric_limits<double>::infinity();
      sum_distortion = std::numeric_limits<double>::infinity();
      continue;
    }
    sum_l2 += 0.5 * (a + c) * tri_area3[t];
    const double gamma = std::sqrt(0.5 * ((a + c) + std::sqrt((a - c) * (a - c) + 4.0 * b * b)));
    max_stretch = std::max(max_stretch, gamma * std::sqrt(norm));
    const double r = (tri_area_uv[t] / norm) / std::max(tri_area3[t], 1e-300);
    sum_distortion += std::max(r, 1.0 / r) * tri_area3[t];
  }
  out.l2 = std::sqrt(sum_l2 / area3 * norm);
  out.max_stretch = max_stretch;
  out.area_distortion = sum_distortion / area3;
  return out;
}

/// One chart during construction.
struct Chart {
  int id = 0;
  std::vector<std::size_t> triangles;  ///< global triangle indices
  std::vector<Index> vertices;         ///< local -> global vertex
  std::vector<Tri> local_triangles;    ///< per chart triangle, local vertex indices
  std::vector<Vec2> uv;                ///< per local vertex, mm after scaling
  UvChartStats stats;
  Vec2 size = Vec2::Zero();    ///< bounding box after rotation, mm
  Vec2 offset = Vec2::Zero();  ///< placement in the atlas, mm
};

std::string chart_name(int id) {
  return "chart " + std::to_string(id);
}

/// Builds the chart's halfedge mesh and checks it is a disk.
SurfaceMesh chart_surface_mesh(const TriMesh& mesh, Chart& chart) {
  std::unordered_map<Index, Index> local;
  chart.local_triangles.reserve(chart.triangles.size());
  for (const std::size_t t : chart.triangles) {
    Tri lt{};
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.triangles[t][static_cast<std::size_t>(k)];
      auto [it, inserted] = local.try_emplace(v, static_cast<Index>(chart.vertices.size()));
      if (inserted) chart.vertices.push_back(v);
      lt[static_cast<std::size_t>(k)] = it->second;
    }
    chart.local_triangles.push_back(lt);
  }
  SurfaceMesh sm;
  for (const Index v : chart.vertices) {
    const Vec3& p = mesh.positions[static_cast<std::size_t>(v)];
    sm.add_vertex(cgal::Point(p.x(), p.y(), p.z()));
  }
  for (std::size_t i = 0; i < chart.local_triangles.size(); ++i) {
    const Tri& t = chart.local_triangles[i];
    const auto f = sm.add_face(SurfaceMesh::Vertex_index(static_cast<std::uint32_t>(t[0])),
                               SurfaceMesh::Vertex_index(static_cast<std::uint32_t>(t[1])),
                               SurfaceMesh::Vertex_index(static_cast<std::uint32_t>(t[2])));
    if (f == SurfaceMesh::null_face()) {
      throw InputError(source, chart_name(chart.id),
                       "is not a topological disk: triangle " + std::to_string(chart.triangles[i]) +
                           " makes a non-manifold edge or vertex or has the opposite orientation");
    }
  }
  // Boundary loops.
  std::size_t loops = 0;
  std::vector<bool> seen(sm.num_halfedges(), false);
  for (const auto h : sm.halfedges()) {
    if (!sm.is_border(h) || seen[h.idx()]) continue;
    ++loops;
    auto g = h;
    do {
      seen[g.idx()] = true;
      g = sm.next(g);
    } while (g != h && !seen[g.idx()]);
  }
  const long long euler = static_cast<long long>(sm.number_of_vertices()) -
                          static_cast<long long>(sm.number_of_edges()) + static_cast<long long>(sm.number_of_faces());
  // Surface_mesh accepts vertices with two fans (pinched); a disk has none.
  for (const auto v : sm.vertices()) {
    if (sm.is_isolated(v)) continue;
    std::size_t border_out = 0;
    for (const auto h : CGAL::halfedges_around_target(v, sm)) {
      if (sm.is_border(h)) ++border_out;
    }
    if (border_out > 1) {
      throw InputError(source, chart_name(chart.id),
                       "is not a topological disk: vertex " +
                           std::to_string(chart.vertices[static_cast<std::size_t>(v.idx())]) +
                           " is pinched (two triangle fans meet there)");
    }
  }
  if (loops != 1 || euler != 1) {
    throw InputError(source, chart_name(chart.id),
                     "is not a topological disk: " + std::to_string(loops) +
                         " boundary loop(s) and Euler characteristic " + std::to_string(euler) +
                         " (a disk has 1 and 1)");
  }
  return sm;
}

template <typename Parameterizer>
bool flatten_with(SurfaceMesh& sm, Parameterizer parameterizer, std::vector<Vec2>& uv) {
  SurfaceMesh::Halfedge_index border;
  for (const auto h : sm.halfedges()) {
    if (sm.is_border(h)) {
      border = h;
      break;
    }
  }
  auto [uvmap, created] = sm.add_property_map<SurfaceMesh::Vertex_index, Point2>("v:forensim_uv", Point2(0, 0));
  (void)created;
  const SMP::Error_code status = SMP::parameterize(sm, parameterizer, border, uvmap);
  uv.assign(sm.number_of_vertices(), Vec2::Zero());
  bool finite = true;
  for (const auto v : sm.vertices()) {
    const Point2& p = uvmap[v];
    uv[v.idx()] = Vec2(p.x(), p.y());
    finite = finite && std::isfinite(p.x()) && std::isfinite(p.y());
  }
  sm.remove_property_map(uvmap);
  return status == SMP::OK && finite;
}

/// Triangle corners of a chart in 3D and UV, for measure_stretch().
void chart_corners(const TriMesh& mesh, const Chart& chart, const std::vector<Vec2>& uv,
                   std::vector<std::array<Vec3, 3>>& surface, std::vector<std::array<Vec2, 3>>& corners) {
  surface.resize(chart.local_triangles.size());
  corners.resize(chart.local_triangles.size());
  for (std::size_t i = 0; i < chart.local_triangles.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto lv = static_cast<std::size_t>(chart.local_triangles[i][k]);
      surface[i][k] = mesh.positions[static_cast<std::size_t>(chart.vertices[lv])];
      corners[i][k] = uv[lv];
    }
  }
}

/// Mirrors the UVs if the chart came out clockwise, so UV triangles keep the surface's orientation.
void orient_counter_clockwise(const Chart& chart, std::vector<Vec2>& uv) {
  double signed_area = 0.0;
  for (const Tri& t : chart.local_triangles) {
    const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]),
               c = static_cast<std::size_t>(t[2]);
    signed_area += cross2(uv[b] - uv[a], uv[c] - uv[a]);
  }
  if (signed_area < 0.0) {
    for (Vec2& p : uv) p.x() = -p.x();
  }
}

/// As-rigid-as-possible refinement of a flattening (Liu et al. 2008, local/global iterations with cotangent
/// weights): each triangle's best rotation of its isometric 2D copy (SVD, reflections excluded), then one
/// sparse solve for all UVs. The matrix is factored once. Written here rather than with CGAL's
/// ARAP_parameterizer_3, which re-factors every iteration and whose solve failed on finger-webbed charts.
void arap_refine(const TriMesh& mesh, const Chart& chart, std::vector<Vec2>& uv, int iterations) {
  const std::size_t nt = chart.local_triangles.size(), nv = chart.vertices.size();
  std::vector<std::array<Vec2, 3>> local(nt);
  std::vector<std::array<double, 3>> cot(nt);  // cot of the angle at each corner
  for (std::size_t t = 0; t < nt; ++t) {
    Vec3 q[3];
    for (std::size_t k = 0; k < 3; ++k) {
      q[k] = mesh.positions[static_cast<std::size_t>(
          chart.vertices[static_cast<std::size_t>(chart.local_triangles[t][k])])];
    }
    const Vec3 e1 = q[1] - q[0], e2 = q[2] - q[0];
    const double l1 = e1.norm();
    const double area2 = e1.cross(e2).norm();
    local[t] = {Vec2(0, 0), Vec2(l1, 0), Vec2(l1 > 0 ? e2.dot(e1) / l1 : 0.0, l1 > 0 ? area2 / l1 : 0.0)};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3 a = q[(k + 1) % 3] - q[k], b = q[(k + 2) % 3] - q[k];
      // Clamped so the Laplacian stays positive definite on obtuse triangles.
      cot[t][k] = area2 > 0.0 ? std::clamp(a.dot(b) / area2, 1e-3, 1e3) : 1e-3;
    }
  }
  using SparseMatrix = Eigen::SparseMatrix<double>;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(nt * 12 + 1);
  for (std::size_t t = 0; t < nt; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto i = static_cast<int>(chart.local_triangles[t][(k + 1) % 3]);
      const auto j = static_cast<int>(chart.local_triangles[t][(k + 2) % 3]);
      const double w = cot[t][k];
      entries.emplace_back(i, i, w);
      entries.emplace_back(j, j, w);
      entries.emplace_back(i, j, -w);
      entries.emplace_back(j, i, -w);
    }
  }
  entries.emplace_back(0, 0, 1.0);  // pins the translation softly at vertex 0
  SparseMatrix laplacian(static_cast<Eigen::Index>(nv), static_cast<Eigen::Index>(nv));
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<SparseMatrix> solver(laplacian);
  if (solver.info() != Eigen::Success) return;  // keep the input map
  Eigen::MatrixXd rhs(static_cast<Eigen::Index>(nv), 2);
  std::vector<Eigen::Matrix2d> rotation(nt);
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t t = 0; t < nt; ++t) {
      Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
      for (std::size_t k = 0; k < 3; ++k) {
        const auto i = static_cast<std::size_t>(chart.local_triangles[t][(k + 1) % 3]);
        const auto j = static_cast<std::size_t>(chart.local_triangles[t][(k + 2) % 3]);
        cov += cot[t][k] * (uv[i] - uv[j]) * (local[t][(k + 1) % 3] - local[t][(k + 2) % 3]).transpose();
      }
      const Eigen::JacobiSVD<Eigen::Matrix2d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix2d u = svd.matrixU();
      if ((u * svd.matrixV().transpose()).determinant() < 0.0) u.col(1) *= -1.0;
      rotation[t] = u * svd.matrixV().transpose();
    }
    rhs.setZero();
    rhs.row(0) = uv[0].transpose();
    for (std::size_t t = 0; t < nt; ++t) {
      for (std::size_t k = 0; k < 3; ++k) {
        const auto i = static_cast<Eigen::Index>(chart.local_triangles[t][(k + 1) % 3]);
        const auto j = static_cast<Eigen::Index>(chart.local_triangles[t][(k + 2) % 3]);
        const Vec2 d = cot[t][k] * rotation[t] * (local[t][(k + 1) % 3] - local[t][(k + 2) % 3]);
        rhs.row(i) += d.transpose();
        rhs.row(j) -= d.transpose();
      }
    }
    const Eigen::MatrixXd x = solver.solve(rhs);
    if (!x.allFinite()) return;
    for (std::size_t v = 0; v < nv; ++v) uv[v] = x.row(static_cast<Eigen::Index>(v)).transpose();
  }
}

/// Unfolds the few triangles a flattening may leave flipped: interior vertices of flipped triangles (and,
/// as rounds go on, their neighbours) move to the mean of their neighbours (a local Tutte step).
void untangle(const Chart& chart, const std::vector<bool>& on_border, std::vector<Vec2>& uv) {
  std::vector<std::vector<Index>> ring(chart.vertices.size());
  for (const Tri& t : chart.local_triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      ring[static_cast<std::size_t>(t[k])].push_back(t[(k + 1) % 3]);
      ring[static_cast<std::size_t>(t[k])].push_back(t[(k + 2) % 3]);
    }
  }
  for (int round = 0; round < 200; ++round) {
    std::vector<Index> active;
    for (const Tri& t : chart.local_triangles) {
      const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]),
                 c = static_cast<std::size_t>(t[2]);
      if (cross2(uv[b] - uv[a], uv[c] - uv[a]) <= 0.0) active.insert(active.end(), t.begin(), t.end());
    }
    if (active.empty()) return;
    for (int grow = 0; grow < round / 20; ++grow) {  // widen the region when a small one does not unfold
      const std::size_t n = active.size();
      for (std::size_t i = 0; i < n; ++i) {
        const auto& r = ring[static_cast<std::size_t>(active[i])];
        active.insert(active.end(), r.begin(), r.end());
      }
      std::sort(active.begin(), active.end());
      active.erase(std::unique(active.begin(), active.end()), active.end());
    }
    std::sort(active.begin(), active.end());
    active.erase(std::unique(active.begin(), active.end()), active.end());
    for (const Index v : active) {
      if (on_border[static_cast<std::size_t>(v)]) continue;
      Vec2 sum = Vec2::Zero();
      for (const Index w : ring[static_cast<std::size_t>(v)]) sum += uv[static_cast<std::size_t>(w)];
      uv[static_cast<std::size_t>(v)] = sum / static_cast<double>(ring[static_cast<std::size_t>(v)].size());
    }
  }
}

/// Pairs of border edges of a flattened chart that cross (exact orientation tests on the doubles; edges
/// sharing a vertex are skipped). A chart without flipped triangles overlaps itself exactly when its border
/// crosses itself.
std::size_t border_crossings(const std::vector<std::array<Index, 2>>& border, const std::vector<Vec2>& uv) {
  const auto orient = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double d = cross2(b - a, c - a);
    return d > 0.0 ? 1 : (d < 0.0 ? -1 : 0);
  };
  std::size_t crossings = 0;
  for (std::size_t i = 0; i < border.size(); ++i) {
    const Vec2& a = uv[static_cast<std::size_t>(border[i][0])];
    const Vec2& b = uv[static_cast<std::size_t>(border[i][1])];
    const Vec2 lo_i = a.cwiseMin(b), hi_i = a.cwiseMax(b);
    for (std::size_t j = i + 1; j < border.size(); ++j) {
      if (border[j][0] == border[i][0] || border[j][0] == border[i][1] || border[j][1] == border[i][0] ||
          border[j][1] == border[i][1]) {
        continue;
      }
      const Vec2& c = uv[static_cast<std::size_t>(border[j][0])];
      const Vec2& d = uv[static_cast<std::size_t>(border[j][1])];
      if ((c.cwiseMax(d).array() < lo_i.array()).any() || (c.cwiseMin(d).array() > hi_i.array()).any()) continue;
      if (orient(a, b, c) * orient(a, b, d) <= 0 && orient(c, d, a) * orient(c, d, b) <= 0) ++crossings;
    }
  }
  return crossings;
}

/// Vertices around which the flattened triangles wind more than once (UV angle sum above 2 pi on the
/// border, different from 2 pi inside): folds that leave every triangle positively oriented.
std::size_t winding_vertices(const Chart& chart, const std::vector<bool>& on_border, const std::vector<Vec2>& uv) {
  std::vector<double> angle(uv.size(), 0.0);
  for (const Tri& t : chart.local_triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec2& p = uv[static_cast<std::size_t>(t[k])];
      const Vec2 a = uv[static_cast<std::size_t>(t[(k + 1) % 3])] - p,
                 b = uv[static_cast<std::size_t>(t[(k + 2) % 3])] - p;
      angle[static_cast<std::size_t>(t[k])] += std::abs(std::atan2(cross2(a, b), a.dot(b)));
    }
  }
  std::size_t count = 0;
  for (std::size_t v = 0; v < angle.size(); ++v) {
    const double full = 2.0 * std::numbers::pi;
    if (on_border[v] ? angle[v] > full + 1e-6 : std::abs(angle[v] - full) > 1e-6) ++count;
  }
  return count;
}

void flatten_chart(const TriMesh& mesh, Chart& chart, const UvAtlasOptions& options) {
  SurfaceMesh sm = chart_surface_mesh(mesh, chart);
  std::vector<bool> on_border(chart.vertices.size(), false);
  std::vector<std::array<Index, 2>> border;
  for (const auto h : sm.halfedges()) {
    if (!sm.is_border(h)) continue;
    on_border[sm.target(h).idx()] = true;
    border.push_back({static_cast<Index>(sm.source(h).idx()), static_cast<Index>(sm.target(h).idx())});
  }
  std::vector<std::array<Vec3, 3>> surface;
  std::vector<std::array<Vec2, 3>> corners;
  struct Candidate {
    std::string name;
    std::vector<Vec2> uv;
    StretchSums stretch;
    std::size_t crossings = 0;
  };
  std::vector<Candidate> candidates;
  const auto evaluate = [&](const std::string& name, std::vector<Vec2> uv) {
    orient_counter_clockwise(chart, uv);
    chart_corners(mesh, chart, uv, surface, corners);
    const std::size_t crossings = border_crossings(border, uv) + winding_vertices(chart, on_border, uv);
    candidates.push_back({name, std::move(uv), measure_stretch(surface, corners), crossings});
  };
  std::vector<Vec2> lscm;
  if (!flatten_with(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), lscm)) {
    throw NumericError("UV atlas: CGAL's LSCM could not flatten " + chart_name(chart.id) + " (" +
                       std::to_string(chart.triangles.size()) + " triangles)");
  }
  orient_counter_clockwise(chart, lscm);
  const bool try_arap =
      options.flattening == UvFlattening::arap ||
      (options.flattening == UvFlattening::automatic && chart.triangles.size() <= options.arap_max_triangles);
  if (try_arap) {
    std::vector<Vec2> uv = lscm;
    arap_refine(mesh, chart, uv, std::max(1, options.arap_iterations));
    untangle(chart, on_border, uv);
    evaluate("arap", std::move(uv));
  }
  if (options.flattening != UvFlattening::arap || candidates.back().crossings > 0 ||
      candidates.back().stretch.flipped > 0) {
    untangle(chart, on_border, lscm);
    evaluate("lscm", std::move(lscm));
  }
  // Prefer valid maps (no flipped triangles, no border crossing itself), then the lower L2 stretch.
  const Candidate* best = nullptr;
  for (const Candidate& c : candidates) {
    if (best == nullptr || std::make_tuple(c.stretch.flipped, c.crossings, c.stretch.l2) <
                               std::make_tuple(best->stretch.flipped, best->crossings, best->stretch.l2)) {
      best = &c;
    }
  }
  if (best == nullptr) {
    throw NumericError("UV atlas: CGAL could not flatten " + chart_name(chart.id) + " (" +
                       std::to_string(chart.triangles.size()) + " triangles)");
  }
  if (best->stretch.flipped > 0) {
    throw NumericError("UV atlas: flattening " + chart_name(chart.id) + " folded " +
                       std::to_string(best->stretch.flipped) + " triangle(s) over");
  }
  chart.uv = best->uv;
  chart.stats.chart = chart.id;
  chart.stats.triangle_count = chart.triangles.size();
  chart.stats.flattening = best->name;
  chart.stats.l2_stretch = best->stretch.l2;
  chart.stats.max_stretch = best->stretch.max_stretch;
  chart.stats.area_distortion = best->stretch.area_distortion;
  chart.stats.flipped_triangles = best->stretch.flipped;
  chart.stats.self_overlaps = best->crossings;
  // Common density: scale so the chart's UV area equals its surface area (1 UV unit = 1 mm for now).
  chart_corners(mesh, chart, chart.uv, surface, corners);
  double area3 = 0.0, area_uv = 0.0;
  for (std::size_t i = 0; i < surface.size(); ++i) {
    area3 += triangle_area(surface[i][0], surface[i][1], surface[i][2]);
    area_uv += 0.5 * cross2(corners[i][1] - corners[i][0], corners[i][2] - corners[i][0]);
  }
  chart.stats.area_mm2 = area3;
  const double scale = std::sqrt(area3 / area_uv);
  for (Vec2& p : chart.uv) p *= scale;
}

/// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (points.size() < 3) return points;
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(hull[k - 1] - hull[k - 2], points[i - 1] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

/// Rotates the chart to its minimum-area bounding rectangle (one side is collinear with a hull edge,
/// Freeman and Shapira 1975), landscape, with its lower-left corner at the origin.
void orient_chart(Chart& chart) {
  const std::vector<Vec2> hull = convex_hull(chart.uv);
  double best_area = std::numeric_limits<double>::infinity(), best_angle = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() <= 0.0) continue;
    const double angle = -std::atan2(e.y(), e.x());
    const Eigen::Rotation2Dd r(angle);
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& p : hull) {
      const Vec2 q = r * p;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const double area = (hi - lo).prod();
    if (area < best_area) {
      best_area = area;
      best_angle = angle;
    }
  }
  const Eigen::Rotation2Dd r(best_angle);
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Vec2& p : chart.uv) {
    p = r * p;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (Vec2& p : chart.uv) p -= lo;
  chart.size = hi - lo;
  if (chart.size.y() > chart.size.x()) {  // quarter turn: (x, y) -> (h - y, x), still counter-clockwise
    const double h = chart.size.y();
    for (Vec2& p : chart.uv) p = Vec2(h - p.y(), p.x());
    chart.size = Vec2(chart.size.y(), chart.size.x());
  }
}

/// Shelf packing into a square of side `side` mm with `gutter` mm between charts and from the border.
/// Returns the height used (mm); charts are placed tallest first.
double shelf_pack(std::vector<Chart>& charts, const std::vector<std::size_t>& order, double side, double gutter) {
  double x = gutter, y = gutter, shelf_height = 0.0;
  for (const std::size_t i : order) {
    Chart& c = charts[i];
    if (x + c.size.x() + gutter > side && x > gutter) {
      y += shelf_height + gutter;
      x = gutter;
      shelf_height = 0.0;
    }
    c.offset = Vec2(x, y);
    x += c.size.x() + gutter;
    shelf_height = std::max(shelf_height, c.size.y());
  }
  return y + shelf_height + gutter;
}

}  // namespace

UvAtlas make_uv_atlas(const TriMesh& mesh, const std::vector<int>& triangle_chart, const UvAtlasOptions& options) {
  mesh.validate("mesh to unwrap");
  require_input(triangle_chart.size() == mesh.triangles.size(), source, "triangle_chart",
                "has " + std::to_string(triangle_chart.size()) + " ids for " + std::to_string(mesh.triangles.size()) +
                    " triangles");
  require_input(!mesh.triangles.empty(), source, "mesh", "has no triangles");
  require_input(options.resolution >= 8 && options.resolution <= 65536, source, "resolution",
                "must be in [8, 65536], got " + std::to_string(options.resolution));
  require_input(options.gutter_texels >= 0 && options.gutter_texels * 4 < options.resolution, source, "gutter_texels",
                "must be in [0, resolution / 4), got " + std::to_string(options.gutter_texels));
  std::map<int, std::size_t> chart_index;
  for (std::size_t t = 0; t < triangle_chart.size(); ++t) {
    if (triangle_chart[t] < 0)
      throw InputError(source, "triangle " + std::to_string(t),
                       "has negative chart id " + std::to_string(triangle_chart[t]));
    chart_index.emplace(triangle_chart[t], 0);
  }
  std::vector<Chart> charts;
  for (auto& [id, index] : chart_index) {
    index = charts.size();
    charts.emplace_back();
    charts.back().id = id;
  }
  for (std::size_t t = 0; t < triangle_chart.size(); ++t) charts[chart_index[triangle_chart[t]]].triangles.push_back(t);
  // Charts are independent: flatten them in parallel (each result depends only on its chart).
  std::vector<std::exception_ptr> errors(charts.size());
  parallel_for(
      0, charts.size(),
      [&](std::size_t i) {
        try {
          flatten_chart(mesh, charts[i], options);
          orient_chart(charts[i]);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      },
      1);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }

  // Pack: grow the square until the shelves fit; the gutter is fixed in texels, so in mm it scales with it.
  std::vector<std::size_t> order(charts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return charts[a].size.y() != charts[b].size.y() ? charts[a].size.y() > charts[b].size.y()
                                                    : charts[a].id < charts[b].id;
  });
  double total = 0.0, widest = 0.0;
  for (const Chart& c : charts) {
    total += c.size.prod();
    widest = std::max(widest, c.size.x());
  }
  const double gutter_fraction = static_cast<double>(options.gutter_texels) / options.resolution;
  double side = std::max(std::sqrt(total), widest) / (1.0 - 2.0 * gutter_fraction);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const double gutter = gutter_fraction * side;
    if (widest + 2.0 * gutter <= side && shelf_pack(charts, order, side, gutter) <= side) break;
    side *= 1.01;
  }

  UvAtlas atlas;
  atlas.mesh = mesh;
  atlas.triangle_chart = triangle_chart;
  atlas.mesh.uvs.clear();
  atlas.mesh.triangle_uvs.assign(mesh.triangles.size(), Tri{0, 0, 0});
  for (const Chart& c : charts) {
    const auto base = static_cast<Index>(atlas.mesh.uvs.size());
    for (const Vec2& p : c.uv) atlas.mesh.uvs.push_back((p + c.offset) / side);
    for (std::size_t i = 0; i < c.triangles.size(); ++i) {
      const Tri& lt = c.local_triangles[i];
      atlas.mesh.triangle_uvs[c.triangles[i]] = Tri{base + lt[0], base + lt[1], base + lt[2]};
    }
    atlas.charts.push_back(c.stats);
  }

  UvAtlasStats& stats = atlas.stats;
  stats.mm_per_uv_unit = side;
  stats.l2_stretch = uv_l2_stretch(atlas.mesh);
  double weighted_distortion = 0.0, area = 0.0, uv_area = 0.0;
  for (const UvChartStats& c : atlas.charts) {
    stats.max_chart_l2_stretch = std::max(stats.max_chart_l2_stretch, c.l2_stretch);
    weighted_distortion += c.area_distortion * c.area_mm2;
    area += c.area_mm2;
  }
  stats.area_distortion = weighted_distortion / area;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& tu = atlas.mesh.triangle_uvs[t];
    const auto& uv = atlas.mesh.uvs;
    uv_area += 0.5 * cross2(uv[static_cast<std::size_t>(tu[1])] - uv[static_cast<std::size_t>(tu[0])],
                            uv[static_cast<std::size_t>(tu[2])] - uv[static_cast<std::size_t>(tu[0])]);
  }
  stats.packing_efficiency = uv_area;
  stats.overlap_free = !uv_triangles_overlap(atlas.mesh, std::min(2 * options.resolution, 8192));
  {
    // Seam edges: an edge whose two triangles lie in different charts.
    std::unordered_map<std::uint64_t, int> first_chart;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        Index a = mesh.triangles[t][static_cast<std::size_t>(k)],
              b = mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
        if (a > b) std::swap(a, b);
        const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
        auto [it, inserted] = first_chart.try_emplace(key, triangle_chart[t]);
        if (!inserted && it->second != triangle_chart[t]) ++stats.seam_edge_count;
      }
    }
  }
  return atlas;
}

double uv_l2_stretch(const TriMesh& mesh) {
  mesh.validate("mesh with UVs");
  require_input(mesh.has_uvs(), "mesh with UVs", "", "has no UVs");
  std::vector<std::array<Vec3, 3>> surface(mesh.triangles.size());
  std::vector<std::array<Vec2, 3>> corners(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      surface[t][k] = mesh.positions[static_cast<std::size_t>(mesh.triangles[t][k])];
      corners[t][k] = mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][k])];
    }
  }
  return measure_stretch(surface, corners).l2;
}

std::size_t uv_overlap_texels(const TriMesh& mesh, int resolution) {
  mesh.validate("mesh with UVs");
  require_input(mesh.has_uvs(), "mesh with UVs", "", "has no UVs");
  require_input(resolution >= 1 && resolution <= 16384, "UV overlap test", "resolution",
                "must be in [1, 16384], got " + std::to_string(resolution));
  const auto n = static_cast<std::size_t>(resolution);
  std::vector<std::uint8_t> count(n * n, 0);
  std::size_t overlapping = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Vec2 p[3];
    for (std::size_t k = 0; k < 3; ++k) p[k] = mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][k])] * resolution;
    const double area2 = cross2(p[1] - p[0], p[2] - p[0]);
    if (area2 == 0.0) continue;
    const double sign = area2 > 0.0 ? 1.0 : -1.0;
    const double x0 = std::min({p[0].x(), p[1].x(), p[2].x()}), x1 = std::max({p[0].x(), p[1].x(), p[2].x()});
    const double y0 = std::min({p[0].y(), p[1].y(), p[2].y()}), y1 = std::max({p[0].y(), p[1].y(), p[2].y()});
    const int ix0 = std::max(0, static_cast<int>(std::floor(x0 - 0.5))),
              ix1 = std::min(resolution - 1, static_cast<int>(std::ceil(x1)));
    const int iy0 = std::max(0, static_cast<int>(std::floor(y0 - 0.5))),
              iy1 = std::min(resolution - 1, static_cast<int>(std::ceil(y1)));
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) {
        const Vec2 c(ix + 0.5, iy + 0.5);
        const double w0 = sign * cross2(p[1] - c, p[2] - c);
        const double w1 = sign * cross2(p[2] - c, p[0] - c);
        const double w2 = sign * cross2(p[0] - c, p[1] - c);
        if (w0 > 0.0 && w1 > 0.0 && w2 > 0.0) {
          std::uint8_t& k = count[static_cast<std::size_t>(iy) * n + static_cast<std::size_t>(ix)];
          if (k == 1) ++overlapping;
          if (k < 2) ++k;
        }
      }
    }
  }
  return overlapping;
}

bool uv_triangles_overlap(const TriMesh& mesh, int resolution) {
  return uv_overlap_texels(mesh, resolution) > 0;
}

std::size_t uv_outside_unit_square(const TriMesh& mesh, double margin) {
  std::size_t outside = 0;
  for (const Vec2& uv : mesh.uvs) {
    if (!(uv.x() >= margin && uv.x() <= 1.0 - margin && uv.y() >= margin && uv.y() <= 1.0 - margin)) ++outside;
  }
  return outside;
}

namespace {
std::uint64_t chart_edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

std::vector<std::array<std::int32_t, 3>> triangle_edge_neighbours(const TriMesh& mesh) {
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> edges;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      edges[chart_edge_key(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3])].push_back(
          static_cast<std::int32_t>(t));
    }
  }
  std::vector<std::array<std::int32_t, 3>> out(mesh.triangles.size(), {-1, -1, -1});
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& users = edges[chart_edge_key(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3])];
      if (users.size() == 2) out[t][k] = users[0] == static_cast<std::int32_t>(t) ? users[1] : users[0];
    }
  }
  return out;
}

std::size_t merge_chart_islands(const std::vector<std::array<std::int32_t, 3>>& neighbours, std::vector<int>& chart) {
  const std::size_t n = chart.size();
  std::vector<std::int32_t> component(n, -1);
  std::vector<std::vector<std::int32_t>> members;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (component[seed] >= 0) continue;
    const auto id = static_cast<std::int32_t>(members.size());
    members.emplace_back();
    std::vector<std::int32_t> stack{static_cast<std::int32_t>(seed)};
    component[seed] = id;
    while (!stack.empty()) {
      const std::int32_t t = stack.back();
      stack.pop_back();
      members.back().push_back(t);
      for (const std::int32_t u : neighbours[static_cast<std::size_t>(t)]) {
        if (u >= 0 && component[static_cast<std::size_t>(u)] < 0 &&
            chart[static_cast<std::size_t>(u)] == chart[static_cast<std::size_t>(t)]) {
          component[static_cast<std::size_t>(u)] = id;
          stack.push_back(u);
        }
      }
    }
  }
  std::map<int, std::size_t> largest;  // chart -> component index
  for (std::size_t c = 0; c < members.size(); ++c) {
    const int label = chart[static_cast<std::size_t>(members[c][0])];
    auto [it, inserted] = largest.try_emplace(label, c);
    if (!inserted && members[c].size() > members[it->second].size()) it->second = c;
  }
  std::size_t moved = 0;
  for (std::size_t c = 0; c < members.size(); ++c) {
    const int label = chart[static_cast<std::size_t>(members[c][0])];
    if (largest[label] == c) continue;
    std::map<int, int> votes;
    for (const std::int32_t t : members[c]) {
      for (const std::int32_t u : neighbours[static_cast<std::size_t>(t)]) {
        if (u >= 0 && chart[static_cast<std::size_t>(u)] != label) ++votes[chart[static_cast<std::size_t>(u)]];
      }
    }
    if (votes.empty()) continue;
    const int target = std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
                         return a.second < b.second;
                       })->first;
    for (const std::int32_t t : members[c]) chart[static_cast<std::size_t>(t)] = target;
    moved += members[c].size();
  }
  return moved;
}

}  // namespace forensim
