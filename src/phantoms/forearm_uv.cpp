#include "phantoms/forearm_uv.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <unordered_map>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "mesh_processing/uv_atlas.hpp"
#include "phantoms/arm_phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "phantoms/sdf.hpp"

namespace forensim {
namespace {

constexpr int cut_chart = 0, dorsal_chart = 1;
constexpr int first_digit_part = 3;  // ArmPhantom parts: forearm, wrist, palm, then thumb, index, middle, ring, little

/// The arm phantom with its fingers kept apart. Its SDF leaves gaps of only about 0.3 mm between
/// neighbouring fingers (the smooth unions fill them), which iso-surfacing at 1.5 to 2 mm fuses in places,
/// giving the skin handles (tunnels between the web and a fused spot) that no disk chart layout can cover.
/// From 14 mm past each finger's base joint on, the skin is clipped to 0.5 mm around the digits' capsule
/// chains (their own surfaces are 2 mm and more apart there); the web and the palm are unchanged.
class SeparatedFingersArm final : public Phantom {
 public:
  std::string name() const override { return m_arm.name(); }
  double skin_distance(const Vec3& p) const override {
    const double d = m_arm.skin_distance(p);
    if (d > 3.0) return d;
    double digits = std::numeric_limits<double>::infinity(), along = -1e9;
    for (const ArmPhantom::Digit& digit : m_arm.digits()) {
      double c = std::numeric_limits<double>::infinity();
      for (int s = 0; s < 3; ++s) {
        if (digit.joints[static_cast<std::size_t>(s)] == digit.joints[static_cast<std::size_t>(s + 1)]) continue;
        c = std::min(
            c, sdf::capsule(p, digit.joints[static_cast<std::size_t>(s)], digit.joints[static_cast<std::size_t>(s + 1)],
                            digit.radii[static_cast<std::size_t>(s)], digit.radii[static_cast<std::size_t>(s + 1)]));
      }
      if (c < digits) {
        digits = c;
        const Vec3 axis = (digit.joints[1] - digit.joints[0]).normalized();
        along = digit.name == "thumb" ? -1e9 : (p - digit.joints[0]).dot(axis);
      }
    }
    if (along < 8.0) return d;
    const double margin = 0.5 + 50.0 * std::clamp((14.0 - along) / 6.0, 0.0, 1.0);
    // Smooth intersection (k = 3 mm): a sharp crease where the gap opens would leave saddle vertices with
    // angle sums near 3 pi, which no flattening lays flat without folding.
    return -sdf::smooth_union(-d, -(digits - margin), 3.0);
  }
  double bone_distance(const Vec3& p) const override { return m_arm.bone_distance(p); }
  BoundingBox bounds() const override { return m_arm.bounds(); }
  const std::vector<std::string>& part_names() const override { return m_arm.part_names(); }
  int part_at(const Vec3& p) const override { return m_arm.part_at(p); }

 private:
  ArmPhantom m_arm;
};

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

/// Straightens chart borders: a triangle with two or three neighbours in one other chart (a spike or a notch
/// of the border) joins that chart. Each move shortens the border, so this ends. Jagged borders make
/// boundary triangles that a free-border flattening can fold over their neighbours.
std::size_t straighten_borders(const std::vector<std::array<std::int32_t, 3>>& neighbours, std::vector<int>& chart) {
  std::size_t moved = 0;
  for (std::size_t t = 0; t < chart.size(); ++t) {
    const auto& nb = neighbours[t];
    for (std::size_t k = 0; k < 3; ++k) {
      if (nb[k] < 0) continue;
      const int other = chart[static_cast<std::size_t>(nb[k])];
      if (other == chart[t]) continue;
      int count = 0;
      for (const std::int32_t u : nb) count += u >= 0 && chart[static_cast<std::size_t>(u)] == other ? 1 : 0;
      if (count >= 2) {
        chart[t] = other;
        ++moved;
        break;
      }
    }
  }
  return moved;
}

/// Where a chart touches itself only at a vertex (its triangles around the vertex form more than one fan
/// sector) or turns around a border vertex by more than 1.6 pi, gives every triangle around that vertex the
/// majority chart there. Returns triangles moved.
std::size_t remove_pinches(const TriMesh& mesh, const std::vector<std::array<std::int32_t, 3>>& neighbours,
                           std::vector<int>& chart) {
  std::vector<std::vector<std::int32_t>> fan(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const Index v : mesh.triangles[t]) fan[static_cast<std::size_t>(v)].push_back(static_cast<std::int32_t>(t));
  }
  std::size_t moved = 0;
  for (std::size_t v = 0; v < fan.size(); ++v) {
    // Count, per chart, the edges at v that separate it from another chart: a chart forming one sector
    // around an interior vertex has two of them.
    std::map<int, int> boundary_edges;
    for (const std::int32_t t : fan[v]) {
      const Tri& f = mesh.triangles[static_cast<std::size_t>(t)];
      for (std::size_t k = 0; k < 3; ++k) {
        if (static_cast<std::size_t>(f[k]) != v && static_cast<std::size_t>(f[(k + 1) % 3]) != v) continue;
        const std::int32_t u = neighbours[static_cast<std::size_t>(t)][k];
        if (u >= 0 && chart[static_cast<std::size_t>(u)] != chart[static_cast<std::size_t>(t)]) {
          ++boundary_edges[chart[static_cast<std::size_t>(t)]];
        }
      }
    }
    bool pinched = false;
    for (const auto& [label, count] : boundary_edges) pinched = pinched || count > 2;
    if (!boundary_edges.empty()) {
      // A chart whose border turns around v by more than 1.6 pi (a deep notch, or a saddle) would have to overlap
      // itself when flattened, whatever the method: conformal maps keep the angle.
      std::map<int, double> angle;
      for (const std::int32_t t : fan[v]) {
        const Tri& f = mesh.triangles[static_cast<std::size_t>(t)];
        std::size_t k = 0;
        while (static_cast<std::size_t>(f[k]) != v) ++k;
        const Vec3& p = mesh.positions[v];
        const Vec3 a = mesh.positions[static_cast<std::size_t>(f[(k + 1) % 3])] - p;
        const Vec3 b = mesh.positions[static_cast<std::size_t>(f[(k + 2) % 3])] - p;
        angle[chart[static_cast<std::size_t>(t)]] += std::atan2(a.cross(b).norm(), a.dot(b));
      }
      for (const auto& [label, sum] : angle) pinched = pinched || sum > 1.6 * std::numbers::pi;
    }
    if (!pinched) continue;
    std::map<int, int> votes;
    for (const std::int32_t t : fan[v]) ++votes[chart[static_cast<std::size_t>(t)]];
    const int target = std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
                         return a.second < b.second;
                       })->first;
    for (const std::int32_t t : fan[v]) {
      if (chart[static_cast<std::size_t>(t)] != target) {
        chart[static_cast<std::size_t>(t)] = target;
        ++moved;
      }
    }
  }
  return moved;
}

/// Initial charts: the flat cut end, then each digit apart from the hand (ArmPhantom::part_at), and each part
/// dorsal or palmar by the smoothed normal z at the triangle.
std::vector<int> assign_charts(const TriMesh& mesh, const ArmPhantom& arm, const ForearmUvOptions& options) {
  const std::vector<Vec3> face_n = face_normals(mesh);
  // Smooth the normal z over the surface (uniform Laplacian) so the seams do not zig-zag.
  std::vector<double> field(mesh.positions.size());
  for (std::size_t v = 0; v < field.size(); ++v) field[v] = mesh.normals[v].z();
  const auto edges = unique_edges(mesh.triangles);
  for (int it = 0; it < options.seam_smoothing_iterations; ++it) {
    std::vector<double> sum(field.size(), 0.0);
    std::vector<int> count(field.size(), 0);
    for (const auto& e : edges) {
      const auto a = static_cast<std::size_t>(e[0]), b = static_cast<std::size_t>(e[1]);
      sum[a] += field[b];
      sum[b] += field[a];
      ++count[a];
      ++count[b];
    }
    for (std::size_t v = 0; v < field.size(); ++v) {
      if (count[v] > 0) field[v] = 0.5 * field[v] + 0.5 * sum[v] / count[v];
    }
  }
  std::vector<int> chart(mesh.triangles.size(), dorsal_chart);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    const Vec3 centre =
        (mesh.positions[static_cast<std::size_t>(f[0])] + mesh.positions[static_cast<std::size_t>(f[1])] +
         mesh.positions[static_cast<std::size_t>(f[2])]) /
        3.0;
    if (centre.x() < 0.5 * options.edge_mm && face_n[t].x() < -0.7) {
      chart[t] = cut_chart;
      continue;
    }
    const double s = (field[static_cast<std::size_t>(f[0])] + field[static_cast<std::size_t>(f[1])] +
                      field[static_cast<std::size_t>(f[2])]) /
                     3.0;
    const int part = arm.part_at(centre);
    int side = s > -options.palmar_split ? 0 : 1;
    if (part >= first_digit_part) {
      // Digits by position: above or below the plane through the digit's axis (lowered by palmar_split
      // radii), which halves the fingertip dome, where a split by normal would leave one chart wrapping over the
      // tip (more than a hemisphere, which no flattening lays flat without folding).
      const std::string& name = arm.part_names()[static_cast<std::size_t>(part)];
      for (const ArmPhantom::Digit& digit : arm.digits()) {
        if (digit.name != name) continue;
        double best = std::numeric_limits<double>::infinity(), height = 0.0;
        for (std::size_t j = 0; j < 3; ++j) {
          const Vec3 a = digit.joints[j], b = digit.joints[j + 1];
          if (a == b) continue;
          const Vec3 axis = (b - a).normalized();
          const double along = std::clamp((centre - a).dot(axis), 0.0, (b - a).norm());
          const double r = digit.radii[j] + (digit.radii[j + 1] - digit.radii[j]) * along / (b - a).norm();
          const Vec3 offset = centre - (a + along * axis);
          const double distance = offset.norm() - r;
          if (distance < best) {
            best = distance;
            const Vec3 up = (Vec3::UnitZ() - axis * axis.z()).normalized();
            height = offset.dot(up) / r;
          }
        }
        side = height > -options.palmar_split ? 0 : 1;
      }
    }
    chart[t] = part >= first_digit_part ? 3 + 2 * (part - first_digit_part) + side : dorsal_chart + side;
  }
  return chart;
}

}  // namespace

bool seam_is_hidden(const Vec3& normal, bool on_cut_rim) {
  return on_cut_rim || normal.z() < 0.0;
}

ForearmUvModel make_forearm_uv(const ForearmUvOptions& options) {
  const char* const source = "forearm-uv options";
  require_input(options.voxel_mm >= 0.5 && options.voxel_mm <= 5.0, source, "voxel_mm",
                "must be in [0.5, 5], got " + std::to_string(options.voxel_mm));
  require_input(options.edge_mm >= 0.5 * options.voxel_mm && options.edge_mm <= 10.0, source, "edge_mm",
                "must be in [voxel_mm / 2, 10], got " + std::to_string(options.edge_mm));
  require_input(options.palmar_split > -1.0 && options.palmar_split < 1.0, source, "palmar_split",
                "must be in (-1, 1), got " + std::to_string(options.palmar_split));
  require_input(options.resolution >= 64 && options.resolution <= 16384, source, "resolution",
                "must be in [64, 16384], got " + std::to_string(options.resolution));
  require_input(options.seam_smoothing_iterations >= 0 && options.seam_smoothing_iterations <= 1000, source,
                "seam_smoothing_iterations", "must be in [0, 1000]");
  require_input(options.remesh_iterations >= 0 && options.remesh_iterations <= 20, source, "remesh_iterations",
                "must be in [0, 20]");
  ForearmUvModel model;
  Stopwatch watch;
  const SeparatedFingersArm arm;
  TriMesh skin = remesh_isotropic(phantom_surface(arm, PhantomSurface::skin, options.voxel_mm), options.edge_mm,
                                  options.remesh_iterations);
  skin = keep_largest_components(skin, 1);
  compute_normals(skin);
  const long long euler = static_cast<long long>(skin.positions.size()) -
                          static_cast<long long>(unique_edges(skin.triangles).size()) +
                          static_cast<long long>(skin.triangles.size());
  if (euler != 2) {
    throw NumericError("forearm-uv: the skin surface at " + std::to_string(options.voxel_mm) +
                       " mm voxels is not a sphere (Euler characteristic " + std::to_string(euler) +
                       "); fingers fused? try a smaller voxel_mm");
  }
  model.seconds_surface = watch.lap();

  std::vector<int> chart = assign_charts(skin, ArmPhantom(), options);
  const auto neighbours = triangle_edge_neighbours(skin);
  for (int round = 0; round < 50; ++round) {
    const std::size_t moved = merge_chart_islands(neighbours, chart) + straighten_borders(neighbours, chart) +
                              remove_pinches(skin, neighbours, chart);
    model.stats.reassigned_triangles += moved;
    if (moved == 0) break;
  }
  UvAtlasOptions atlas_options;
  atlas_options.resolution = options.resolution;
  atlas_options.gutter_texels = options.gutter_texels;
  UvAtlas atlas = make_uv_atlas(skin, chart, atlas_options);
  model.seconds_atlas = watch.lap();

  model.mesh = std::move(atlas.mesh);
  model.triangle_chart = std::move(chart);
  model.chart_names = {"cut", "dorsal", "palmar"};
  const ArmPhantom plain_arm;
  for (std::size_t part = first_digit_part; part < plain_arm.part_names().size(); ++part) {
    model.chart_names.push_back(plain_arm.part_names()[part] + " dorsal");
    model.chart_names.push_back(plain_arm.part_names()[part] + " palmar");
  }
  ForearmUvStats& stats = model.stats;
  stats.l2_stretch = atlas.stats.l2_stretch;
  stats.max_chart_l2_stretch = atlas.stats.max_chart_l2_stretch;
  stats.area_distortion = atlas.stats.area_distortion;
  stats.packing_efficiency = atlas.stats.packing_efficiency;
  stats.mm_per_uv_unit = atlas.stats.mm_per_uv_unit;
  stats.overlap_free = atlas.stats.overlap_free;
  stats.chart_l2_stretch.assign(model.chart_names.size(), 0.0);
  stats.chart_flattening.assign(model.chart_names.size(), "");
  for (const UvChartStats& c : atlas.charts) {
    if (c.chart < 0 || static_cast<std::size_t>(c.chart) >= model.chart_names.size()) continue;
    stats.chart_l2_stretch[static_cast<std::size_t>(c.chart)] = c.l2_stretch;
    stats.chart_flattening[static_cast<std::size_t>(c.chart)] = c.flattening;
  }
  // Seam length, and how much of it is hidden.
  const std::vector<Vec3> face_n = face_normals(model.mesh);
  std::unordered_map<std::uint64_t, std::int32_t> first;
  double hidden = 0.0;
  for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
    const Tri& f = model.mesh.triangles[t];
    for (std::size_t k = 0; k < 3; ++k) {
      auto [it, inserted] = first.try_emplace(edge_key(f[k], f[(k + 1) % 3]), static_cast<std::int32_t>(t));
      if (inserted) continue;
      const auto u = static_cast<std::size_t>(it->second);
      if (model.triangle_chart[u] == model.triangle_chart[t]) continue;
      const double length = (model.mesh.positions[static_cast<std::size_t>(f[k])] -
                             model.mesh.positions[static_cast<std::size_t>(f[(k + 1) % 3])])
                                .norm();
      const bool rim = model.triangle_chart[u] == cut_chart || model.triangle_chart[t] == cut_chart;
      stats.seam_length_mm += length;
      if (seam_is_hidden((face_n[t] + face_n[u]).normalized(), rim)) hidden += length;
    }
  }
  stats.hidden_seam_fraction = stats.seam_length_mm > 0.0 ? hidden / stats.seam_length_mm : 1.0;
  return model;
}

}  // namespace forensim
