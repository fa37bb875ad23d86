#include "craniofacial/skin_muscle_model.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "core/error.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

void require_positive(double value, const char* name) {
  require_input(std::isfinite(value) && value > 0.0, "skin-muscle model options", name,
                "must be positive and finite, got " + std::to_string(value));
}

}  // namespace

double skull_spring_stiffness(double depth_mm, const SkinMuscleModelOptions& options) {
  if (depth_mm <= options.tight_depth_mm) return options.skull_stiffness;
  if (depth_mm >= options.loose_depth_mm) return options.loose_skull_stiffness;
  const double t = (depth_mm - options.tight_depth_mm) / (options.loose_depth_mm - options.tight_depth_mm);
  const double s = t * t * (3.0 - 2.0 * t);
  return std::exp((1.0 - s) * std::log(options.skull_stiffness) + s * std::log(options.loose_skull_stiffness));
}

SkinMuscleModel make_skin_muscle_model(const TriMesh& skin, const TriMesh& skull,
                                       const std::vector<MuscleShape>& muscles, const SkinMuscleModelOptions& options) {
  require_input(!skin.triangles.empty(), "skin-muscle model skin", "", "the skin mesh has no triangles");
  require_input(!skull.triangles.empty(), "skin-muscle model skull", "", "the skull mesh has no triangles");
  skin.validate("skin-muscle model skin");
  skull.validate("skin-muscle model skull");
  require_positive(options.skin_stiffness, "skin_stiffness");
  require_positive(options.bending_stiffness, "bending_stiffness");
  require_positive(options.skull_stiffness, "skull_stiffness");
  require_positive(options.loose_skull_stiffness, "loose_skull_stiffness");
  require_positive(options.fibre_stiffness, "fibre_stiffness");
  require_positive(options.attachment_stiffness, "attachment_stiffness");
  require_input(std::isfinite(options.tight_depth_mm) && std::isfinite(options.loose_depth_mm) &&
                    options.tight_depth_mm > 0.0 && options.tight_depth_mm < options.loose_depth_mm,
                "skin-muscle model options", "tight_depth_mm, loose_depth_mm",
                "need 0 < tight_depth_mm < loose_depth_mm");

  SkinMuscleModel m;
  const std::size_t nv = skin.positions.size();
  m.skin_node_count = nv;
  m.node_rest_positions = skin.positions;
  m.node_fixed.assign(nv, 0);
  m.attachment_stiffness = options.attachment_stiffness;

  // Skull springs from the tissue depth.
  const ClosestPointQuery skull_query(skull);
  const auto hits = skull_query.query_batch(skin.positions);
  m.node_tissue_depth_mm.resize(nv);
  m.node_skull_stiffness.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    m.node_tissue_depth_mm[i] = hits[i]->distance;
    m.node_skull_stiffness[i] = skull_spring_stiffness(hits[i]->distance, options);
  }

  // Skin edges and bending springs across interior edges (opposite corners of the two triangles).
  std::vector<std::pair<std::pair<Index, Index>, Index>> edge_corner;  // (edge, opposite corner)
  edge_corner.reserve(3 * skin.triangles.size());
  for (const Tri& t : skin.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Index a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      edge_corner.push_back({{std::min(a, b), std::max(a, b)}, t[static_cast<std::size_t>((k + 2) % 3)]});
    }
  }
  std::sort(edge_corner.begin(), edge_corner.end());
  auto add_spring = [&](Index a, Index b, double k, Index muscle) {
    m.spring_nodes.push_back({a, b});
    m.spring_rest_length_mm.push_back(
        (m.node_rest_positions[static_cast<std::size_t>(a)] - m.node_rest_positions[static_cast<std::size_t>(b)])
            .norm());
    m.spring_stiffness.push_back(k);
    m.spring_muscle.push_back(muscle);
  };
  std::set<std::pair<Index, Index>> bends;
  for (std::size_t i = 0; i < edge_corner.size();) {
    std::size_t j = i;
    while (j < edge_corner.size() && edge_corner[j].first == edge_corner[i].first) ++j;
    add_spring(edge_corner[i].first.first, edge_corner[i].first.second, options.skin_stiffness, -1);
    if (j - i == 2) {
      const Index c = edge_corner[i].second, d = edge_corner[i + 1].second;
      if (c != d) bends.insert({std::min(c, d), std::max(c, d)});
    }
    i = j;
  }
  for (const auto& [c, d] : bends) add_spring(c, d, options.bending_stiffness, -1);

  // Muscles: fibre nodes, segments and attachments.
  std::set<std::string> names;
  for (std::size_t k = 0; k < muscles.size(); ++k) {
    const MuscleShape& s = muscles[k];
    const std::string source = "skin-muscle model muscle " + s.name;
    require_input(names.insert(s.name).second, source, "name", "is repeated");
    const std::size_t n = static_cast<std::size_t>(s.fibre_count) * static_cast<std::size_t>(s.samples_per_fibre);
    require_input(s.fibre_count >= 1 && s.samples_per_fibre >= 2 && s.fibre_points.size() == n &&
                      s.skin_points.size() == n && s.skin_triangles.size() == n && s.skin_barycentrics.size() == n,
                  source, "shape", "sizes do not match fibre_count * samples_per_fibre (use shape_muscles())");
    m.muscle_names.push_back(s.name);
    m.muscle_kinds.push_back(s.kind);
    const Index first = static_cast<Index>(m.node_rest_positions.size());
    for (std::size_t i = 0; i < n; ++i) {
      const Index tri = s.skin_triangles[i];
      require_input(tri >= 0 && static_cast<std::size_t>(tri) < skin.triangles.size() &&
                        std::isfinite(s.fibre_points[i].sum()) && std::isfinite(s.skin_barycentrics[i].sum()),
                    source, "sample " + std::to_string(i), "skin triangle out of range or non-finite point");
      const Index node = static_cast<Index>(m.node_rest_positions.size());
      const bool origin = s.kind == MuscleKind::linear && i % static_cast<std::size_t>(s.samples_per_fibre) == 0;
      m.node_rest_positions.push_back(s.fibre_points[i]);
      m.node_fixed.push_back(origin ? 1 : 0);
      const Tri& t = skin.triangles[static_cast<std::size_t>(tri)];
      const Vec3& w = s.skin_barycentrics[i];
      const Vec3 skin_point = w(0) * skin.positions[static_cast<std::size_t>(t[0])] +
                              w(1) * skin.positions[static_cast<std::size_t>(t[1])] +
                              w(2) * skin.positions[static_cast<std::size_t>(t[2])];
      m.attachment_node.push_back(node);
      m.attachment_triangle.push_back(t);
      m.attachment_barycentric.push_back(w);
      m.attachment_offset.push_back(skin_point - s.fibre_points[i]);
    }
    const std::size_t samples = static_cast<std::size_t>(s.samples_per_fibre);
    for (int f = 0; f < s.fibre_count; ++f) {
      const Index base = first + static_cast<Index>(static_cast<std::size_t>(f) * samples);
      for (std::size_t j = 0; j + 1 < samples; ++j) {
        add_spring(base + static_cast<Index>(j), base + static_cast<Index>(j + 1), options.fibre_stiffness,
                   static_cast<Index>(k));
      }
      if (s.kind == MuscleKind::sphincter) {
        add_spring(base + static_cast<Index>(samples - 1), base, options.fibre_stiffness, static_cast<Index>(k));
      }
    }
  }
  return m;
}

}  // namespace forensim
