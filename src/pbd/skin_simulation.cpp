#include "pbd/skin_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "pbd/collision_constraint.hpp"
#include "pbd/tracking_constraint.hpp"
#include "pbd/velocity_damping.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

void require_fraction(double v, const std::string& source, const std::string& name) {
  require_input(std::isfinite(v) && v >= 0.0 && v <= 1.0, source, name, "must lie in [0, 1]");
}

/// Stiffness per Gauss-Seidel iteration so that n iterations act as one projection of stiffness k
/// (Mueller et al. 2007, section 3.3): k' = 1 - (1 - k)^(1/n).
double per_iteration(double k, int iterations) {
  return 1.0 - std::pow(1.0 - std::clamp(k, 0.0, 1.0), 1.0 / static_cast<double>(iterations));
}

/// Constraints of a colour group per task: below this a group runs on one thread (task overhead would exceed
/// the work).
constexpr std::size_t constraint_grain = 1024;

/// Per-vertex (per-edge, per-face) loops: a few thousand items per task, so a small skin runs on one thread
/// and a large one in a few tasks.
template <class F>
void for_each_item(std::size_t n, const F& body) {
  parallel_for_chunks(
      0, n,
      [&](std::size_t lo, std::size_t hi) {
        for (std::size_t i = lo; i < hi; ++i) body(i);
      },
      2048);
}

struct Contact {
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
  double height = std::numeric_limits<double>::infinity();
};

/// The closest of vertex i's candidate boundary faces to p, with its outward normal and p's height over it (of
/// faces equally close, the one with the lowest index). The tracking face, usually the closest, is tried first, so
/// that the plane test below skips most of the others.
Contact detect_contact(const SkinModel& model, std::size_t i, const Vec3& p, const std::vector<Vec3>& nodes,
                       const std::vector<Vec3>& face_normals) {
  Contact best;
  double best_distance = std::numeric_limits<double>::infinity();
  std::size_t best_face = std::numeric_limits<std::size_t>::max();
  auto consider = [&](std::size_t f) {
    const Tri& tri = model.boundary_face_nodes[f];
    const Vec3& a = nodes[static_cast<std::size_t>(tri[0])];
    // The distance to the face's plane bounds the distance to the face from below: a face whose plane is
    // farther than the best face so far cannot win.
    const double plane = face_normals[f].dot(p - a);
    const double plane2 = plane * plane;
    if (plane2 > best_distance || (plane2 == best_distance && f > best_face)) return;
    const Vec3& b = nodes[static_cast<std::size_t>(tri[1])];
    const Vec3& c = nodes[static_cast<std::size_t>(tri[2])];
    const Vec3 w = closest_point_on_triangle(p, a, b, c);
    const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
    const double d = (p - q).squaredNorm();
    if (d < best_distance || (d == best_distance && f < best_face)) {
      best_distance = d;
      best_face = f;
      best.point = q;
      best.normal = face_normals[f];
    }
  };
  const auto first = static_cast<std::size_t>(model.tracking.boundary_face[i]);
  consider(first);
  for (Index k = model.vertex_collision_offsets[i]; k < model.vertex_collision_offsets[i + 1]; ++k) {
    const auto f = static_cast<std::size_t>(model.vertex_collision_faces[static_cast<std::size_t>(k)]);
    if (f != first) consider(f);
  }
  if (best_distance < std::numeric_limits<double>::infinity()) best.height = best.normal.dot(p - best.point);
  return best;
}

void compute_face_normals(const SkinModel& model, const std::vector<Vec3>& nodes, std::vector<Vec3>& normals) {
  normals.resize(model.boundary_face_nodes.size());
  for_each_item(normals.size(), [&](std::size_t f) {
    const Tri& t = model.boundary_face_nodes[f];
    const Vec3& a = nodes[static_cast<std::size_t>(t[0])];
    const Vec3 n = (nodes[static_cast<std::size_t>(t[1])] - a).cross(nodes[static_cast<std::size_t>(t[2])] - a);
    const double length = n.norm();
    normals[f] = length > 0.0 ? Vec3(n / length) : Vec3::Zero();
  });
}

Vec3 tracking_point(const TrackingConnections& tracking, std::size_t i, const std::vector<Vec3>& nodes) {
  const Tri& f = tracking.face_nodes[i];
  const Vec3& w = tracking.weights[i];
  return w[0] * nodes[static_cast<std::size_t>(f[0])] + w[1] * nodes[static_cast<std::size_t>(f[1])] +
         w[2] * nodes[static_cast<std::size_t>(f[2])];
}

}  // namespace

WrinkleControls WrinkleControls::figure8(int set) {
  switch (set) {
    case 0:
      return {0.001, 0.5};
    case 1:
      return {0.002, 0.2};
    case 2:
      return {0.004, 0.08};
    default:
      throw InputError("wrinkle controls", "set " + std::to_string(set), "is not one of Figure 8's sets (0, 1 or 2)");
  }
}

void SkinSettings::validate(const std::string& source) const {
  require_input(std::isfinite(wrinkle.r_max_relative) && wrinkle.r_max_relative >= 0.0, source,
                "wrinkle.r_max_relative", "must be finite and non-negative");
  require_fraction(wrinkle.damping, source, "wrinkle.damping");
  slippage.validate(source + " slippage");
  require_input(iterations >= 1 && iterations <= 1000, source, "iterations", "must lie in [1, 1000]");
  require_input(bending_interval >= 1 && bending_interval <= 1000, source, "bending_interval", "must lie in [1, 1000]");
  require_fraction(stretch_stiffness_wet, source, "stretch_stiffness_wet");
  require_fraction(stretch_stiffness_dry, source, "stretch_stiffness_dry");
  require_input(std::isfinite(skin_shrinkage) && skin_shrinkage >= 0.0 && skin_shrinkage < 1.0, source,
                "skin_shrinkage", "must lie in [0, 1)");
  require_fraction(bending_stiffness_wet, source, "bending_stiffness_wet");
  require_fraction(bending_stiffness_dry, source, "bending_stiffness_dry");
  require_input(gravity_mm_per_s2.allFinite(), source, "gravity_mm_per_s2", "must be finite");
}

SkinModel make_skin_model(const BodyModel& body, const SkinSettings& settings) {
  settings.validate("skin settings");
  body.validate("body model");
  SkinModel model;
  model.settings = settings;
  model.vertex_rest_position = body.skin.positions;
  model.triangles = body.skin.triangles;
  const std::size_t n = model.vertex_count();
  model.stretch = make_stretch_constraints(model.vertex_rest_position, model.triangles, "skin mesh");
  model.bending = make_bending_constraints(model.vertex_rest_position, model.triangles, "skin mesh");
  model.stretch_groups = color_constraints(model.stretch.edge_vertices, n);
  model.bending_groups = color_constraints(model.bending.quad_vertices, n);

  // Lumped masses: a third of each triangle's area per corner, normalised to mean 1.
  std::vector<double> area(n, 0.0);
  for (const Tri& t : model.triangles) {
    const Vec3& a = model.vertex_rest_position[static_cast<std::size_t>(t[0])];
    const double third = 0.5 *
                         (model.vertex_rest_position[static_cast<std::size_t>(t[1])] - a)
                             .cross(model.vertex_rest_position[static_cast<std::size_t>(t[2])] - a)
                             .norm() /
                         3.0;
    for (Index v : t) area[static_cast<std::size_t>(v)] += third;
  }
  double total = 0.0;
  for (double a : area) total += a;
  const double mean = n > 0 ? total / static_cast<double>(n) : 0.0;
  model.vertex_inverse_mass.resize(n, 1.0);
  for (std::size_t i = 0; i < n; ++i)
    if (area[i] > 0.0 && mean > 0.0) model.vertex_inverse_mass[i] = mean / area[i];

  double edge_sum = 0.0;
  for (double l : model.stretch.edge_rest_length) edge_sum += l;
  model.mean_edge_mm = model.stretch.size() > 0 ? edge_sum / static_cast<double>(model.stretch.size()) : 0.0;
  if (n > 0) {
    Vec3 lo = model.vertex_rest_position[0], hi = lo;
    for (const Vec3& p : model.vertex_rest_position) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    model.model_size_mm = (hi - lo).maxCoeff();
  }
  model.r_max_mm = settings.wrinkle.r_max_relative * model.model_size_mm;

  model.tracking = body.tracking;
  model.vertex_tracking_offset.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    model.vertex_tracking_offset[i] =
        model.vertex_rest_position[i] - tracking_point(body.tracking, i, body.volume.positions);
  model.volume_node_count = body.volume.vertex_count();
  model.boundary_face_nodes.reserve(body.boundary_faces.size());
  for (const TetFace& f : body.boundary_faces) model.boundary_face_nodes.push_back(f.vertices);

  // Collision candidates: the tracking face and every boundary face sharing a node with it.
  std::vector<std::vector<Index>> node_faces(model.volume_node_count);
  for (std::size_t f = 0; f < model.boundary_face_nodes.size(); ++f)
    for (Index v : model.boundary_face_nodes[f])
      node_faces[static_cast<std::size_t>(v)].push_back(static_cast<Index>(f));
  model.vertex_collision_offsets.assign(n + 1, 0);
  std::vector<Index> candidates;
  for (std::size_t i = 0; i < n; ++i) {
    candidates.clear();
    for (Index v : model.tracking.face_nodes[i]) {
      const auto& faces = node_faces[static_cast<std::size_t>(v)];
      candidates.insert(candidates.end(), faces.begin(), faces.end());
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    model.vertex_collision_faces.insert(model.vertex_collision_faces.end(), candidates.begin(), candidates.end());
    model.vertex_collision_offsets[i + 1] = static_cast<Index>(model.vertex_collision_faces.size());
  }
  // Rest heights over the boundary: a skin vertex that starts under it may stay as deep as it started.
  std::vector<Vec3> normals;
  compute_face_normals(model, body.volume.positions, normals);
  model.vertex_collision_floor.assign(n, 0.0);
  for_each_item(n, [&](std::size_t i) {
    const Contact c = detect_contact(model, i, model.vertex_rest_position[i], body.volume.positions, normals);
    model.vertex_collision_floor[i] = std::isfinite(c.height) ? std::min(0.0, c.height) : 0.0;
  });
  return model;
}

SkinState initial_skin_state(const SkinModel& model) {
  SkinState state;
  state.positions = model.vertex_rest_position;
  state.velocities.assign(model.vertex_count(), Vec3::Zero());
  return state;
}

SkinSimulation::SkinSimulation(const SkinModel& model) : m_model(model) {
  m_stretch_offsets.push_back(0);
  for (const auto& group : model.stretch_groups) {
    for (std::uint32_t e : group) {
      const auto& ab = model.stretch.edge_vertices[e];
      m_stretch_vertices.push_back({static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])});
      m_stretch_rest.push_back(model.stretch.edge_rest_length[e]);
    }
    m_stretch_offsets.push_back(m_stretch_vertices.size());
  }
  m_bending_offsets.push_back(0);
  for (const auto& group : model.bending_groups) {
    for (std::uint32_t b : group) {
      const auto& q = model.bending.quad_vertices[b];
      m_bending_vertices.push_back({static_cast<std::uint32_t>(q[0]), static_cast<std::uint32_t>(q[1]),
                                    static_cast<std::uint32_t>(q[2]), static_cast<std::uint32_t>(q[3])});
      m_bending_rest.push_back(model.bending.rest_angle[b]);
    }
    m_bending_offsets.push_back(m_bending_vertices.size());
  }
}

SkinStepReport SkinSimulation::step(SkinState& state, const std::vector<Vec3>& volume_node_positions,
                                    const std::vector<double>& vertex_moisture_ratio, double dt_s) {
  const Stopwatch timer;
  const SkinModel& model = m_model;
  const SkinSettings& settings = model.settings;
  const std::size_t n = model.vertex_count();
  const std::string source = "skin step";
  require_input(state.positions.size() == n && state.velocities.size() == n, source, "state",
                "has " + std::to_string(state.positions.size()) + " positions and " +
                    std::to_string(state.velocities.size()) + " velocities for " + std::to_string(n) +
                    " skin vertices");
  require_input(volume_node_positions.size() == model.volume_node_count, source, "volume node positions",
                "has " + std::to_string(volume_node_positions.size()) + " entries for " +
                    std::to_string(model.volume_node_count) + " volume nodes");
  require_input(
      vertex_moisture_ratio.size() == n, source, "moisture ratio",
      "has " + std::to_string(vertex_moisture_ratio.size()) + " entries for " + std::to_string(n) + " skin vertices");
  require_input(std::isfinite(dt_s) && dt_s > 0.0, source, "dt", "must be positive and finite");
  require_input(state.tracking_points.empty() || state.tracking_points.size() == n, source, "state",
                "has " + std::to_string(state.tracking_points.size()) + " tracking points for " + std::to_string(n) +
                    " skin vertices");
  const int iterations = settings.iterations;
  const TrackingConnections& tracking = model.tracking;
  const std::vector<double>& w = model.vertex_inverse_mass;
  std::vector<Vec3>& x = state.positions;
  std::vector<Vec3>& v = state.velocities;

  // 1. Tracking points, stiffness from moisture.
  compute_face_normals(model, volume_node_positions, m_face_normals);
  m_tracking_points.resize(n);
  m_attach_radius.resize(n);
  m_anchors.resize(n);
  m_outward.assign(n, 0);
  std::vector<std::uint8_t> pulled(n, 0);
  m_moisture.resize(n);
  for_each_item(n, [&](std::size_t i) {
    const double m = vertex_moisture_ratio[i];
    m_moisture[i] = std::isfinite(m) ? std::clamp(m, 0.0, 1.0) : 1.0;
    m_tracking_points[i] = tracking_point(tracking, i, volume_node_positions);
  });
  auto moisture = [&](std::size_t i) { return m_moisture[i]; };
  const int bending_interval = std::min(settings.bending_interval, iterations);
  const int bending_passes = (iterations + bending_interval - 1) / bending_interval;
  // The stiffness and rest lengths depend on the moisture alone: recomputed only when it changed (the substeps
  // of a shape solve share one moisture state).
  if (m_moisture != m_stiffness_moisture) {
    m_stiffness_moisture = m_moisture;
    m_tracking_stiffness.resize(n);
    m_tracking_pass_stiffness.resize(n);
    for_each_item(n, [&](std::size_t i) {
      m_tracking_stiffness[i] = tracking_stiffness(moisture(i), settings.slippage);
      m_tracking_pass_stiffness[i] = per_iteration(m_tracking_stiffness[i], iterations);
    });
    m_edge_stiffness.resize(m_stretch_vertices.size());
    m_edge_rest_length.resize(m_stretch_vertices.size());
    for_each_item(m_stretch_vertices.size(), [&](std::size_t e) {
      const auto& [a, b] = m_stretch_vertices[e];
      const double m = 0.5 * (moisture(static_cast<std::size_t>(a)) + moisture(static_cast<std::size_t>(b)));
      m_edge_stiffness[e] = per_iteration(
          settings.stretch_stiffness_dry + (settings.stretch_stiffness_wet - settings.stretch_stiffness_dry) * m,
          iterations);
      m_edge_rest_length[e] = m_stretch_rest[e] * (1.0 - settings.skin_shrinkage * (1.0 - m));
    });
    m_pair_stiffness.resize(m_bending_vertices.size());
    for_each_item(m_bending_vertices.size(), [&](std::size_t b) {
      double m = 0.0;
      for (std::uint32_t q : m_bending_vertices[b]) m += 0.25 * moisture(q);
      m_pair_stiffness[b] = per_iteration(
          settings.bending_stiffness_dry + (settings.bending_stiffness_wet - settings.bending_stiffness_dry) * m,
          bending_passes);
    });
  }

  // 2. External forces and the pull of inward-facing connections (eq. 34), before damping.
  for_each_item(n, [&](std::size_t i) {
    if (w[i] > 0.0) v[i] += dt_s * settings.gravity_mm_per_s2;
    const Vec3& t = m_tracking_points[i];
    const double k = m_tracking_stiffness[i];
    const Vec3& face_normal = m_face_normals[static_cast<std::size_t>(tracking.boundary_face[i])];
    // Outward facing: the direction from the vertex to its tracking point is along the outward normal, so the
    // vertex lies under the boundary (section 8.2).
    m_outward[i] = face_normal.dot(t - x[i]) > 0.0 ? 1 : 0;
    if (m_outward[i]) {
      // One-sided attachment: stiffness 1 and a constant radius, the connection's rest length.
      m_attach_radius[i] = tracking.rest_distance[i];
      m_anchors[i] = t;
    } else {
      // The slip radius r_j (eq. 33) opens from 0 to r_max as the stiffness falls with the moisture (eq. 35).
      m_anchors[i] = t + model.vertex_tracking_offset[i];
      m_attach_radius[i] = slip_radius_mm(moisture(i), settings.slippage, model.r_max_mm);
      if (k > 0.0) {
        const Vec3 pull = tracking_pull(x[i], m_anchors[i], m_attach_radius[i], k);
        if (pull.squaredNorm() > 0.0) {
          v[i] += pull / dt_s;
          pulled[i] = 1;
        }
      }
    }
  });

  // 3. Damping and prediction.
  if (settings.damping_frame == DampingFrame::rigid_motion) {
    damp_velocities(x, w, v, settings.wrinkle.damping);
  } else {
    m_frame_velocities.resize(n);
    const bool first = state.tracking_points.size() != n;
    for_each_item(n, [&](std::size_t i) {
      m_frame_velocities[i] = first ? Vec3::Zero() : Vec3((m_tracking_points[i] - state.tracking_points[i]) / dt_s);
    });
    damp_relative_velocities(v, m_frame_velocities, settings.wrinkle.damping);
  }
  m_predicted.resize(n);
  for_each_item(n, [&](std::size_t i) { m_predicted[i] = w[i] > 0.0 ? Vec3(x[i] + dt_s * v[i]) : x[i]; });
  std::vector<Vec3>& p = m_predicted;

  // 4. Collision constraints for the predicted positions: a plane through the closest boundary point for every
  // vertex that is under, or within a mean edge of, its allowed height.
  m_plane_points.resize(n);
  m_plane_normals.resize(n);
  m_has_plane.assign(n, 0);
  const double margin = model.mean_edge_mm;
  for_each_item(n, [&](std::size_t i) {
    const Contact c = detect_contact(model, i, p[i], volume_node_positions, m_face_normals);
    if (c.height < model.vertex_collision_floor[i] + margin && c.normal.squaredNorm() > 0.0) {
      m_plane_points[i] = c.point;
      m_plane_normals[i] = c.normal;
      m_has_plane[i] = 1;
    }
  });

  // 5. Gauss-Seidel iterations over independent groups, in colour order from the flat slot arrays.
  const std::size_t stretch_colours = m_stretch_offsets.size() - 1, bending_colours = m_bending_offsets.size() - 1;
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t colour = 0; colour < stretch_colours; ++colour) {
      parallel_for_chunks(
          m_stretch_offsets[colour], m_stretch_offsets[colour + 1],
          [&](std::size_t lo, std::size_t hi) {
            for (std::size_t s = lo; s < hi; ++s) {
              const std::uint32_t a = m_stretch_vertices[s][0], b = m_stretch_vertices[s][1];
              const PairCorrection d =
                  project_stretch(p[a], p[b], w[a], w[b], m_edge_rest_length[s], m_edge_stiffness[s]);
              p[a] += d.dp0;
              p[b] += d.dp1;
            }
          },
          constraint_grain);
    }
    // Bending on the last iteration and every bending_interval-th before it.
    const bool bend = (iterations - 1 - it) % bending_interval == 0;
    for (std::size_t colour = 0; bend && colour < bending_colours; ++colour) {
      parallel_for_chunks(
          m_bending_offsets[colour], m_bending_offsets[colour + 1],
          [&](std::size_t lo, std::size_t hi) {
            for (std::size_t s = lo; s < hi; ++s) {
              const auto& q = m_bending_vertices[s];
              const auto d =
                  project_bending({p[q[0]], p[q[1]], p[q[2]], p[q[3]]}, Vec4(w[q[0]], w[q[1]], w[q[2]], w[q[3]]),
                                  m_bending_rest[s], m_pair_stiffness[s]);
              for (int k = 0; k < 4; ++k) p[q[k]] += d[k];
            }
          },
          constraint_grain);
    }
    for_each_item(n, [&](std::size_t i) {
      if (w[i] <= 0.0) return;
      if (m_outward[i]) {
        p[i] += project_tracking(p[i], m_tracking_points[i], 1.0, 0.0, m_attach_radius[i], 1.0).dp0;
      } else {
        // Pulled towards the anchor beyond r_j with k_j, and never farther than r_max from it.
        const double k = settings.hold_inward ? m_tracking_pass_stiffness[i] : 0.0;
        p[i] += project_tracking_bounded(p[i], m_anchors[i], m_attach_radius[i], k, model.r_max_mm);
      }
      if (m_has_plane[i])
        p[i] +=
            project_collision(p[i], m_plane_points[i], m_plane_normals[i], 1.0, 0.0, model.vertex_collision_floor[i])
                .dp0;
    });
  }

  // 6. Velocities from the position change.
  std::vector<std::uint8_t> bad(n, 0);
  for_each_item(n, [&](std::size_t i) {
    if (!p[i].allFinite()) bad[i] = 1;
    v[i] = (p[i] - x[i]) / dt_s;
    x[i] = p[i];
  });
  for (std::size_t i = 0; i < n; ++i)
    if (bad[i]) throw NumericError("skin step: skin vertex " + std::to_string(i) + " has a non-finite position");

  SkinStepReport report;
  for (std::size_t i = 0; i < n; ++i) {
    report.pulled += pulled[i];
    report.attached += m_outward[i];
    report.collisions += m_has_plane[i];
    if (m_tracking_stiffness[i] <= 0.0) {
      ++report.slipped;
      continue;
    }
    report.max_tracking_excess_mm =
        std::max(report.max_tracking_excess_mm, tracking_value(x[i], m_anchors[i], m_attach_radius[i]));
  }
  state.tracking_points = m_tracking_points;
  state.time_s += dt_s;
  ++state.step_count;
  report.seconds = timer.seconds();
  return report;
}

std::vector<double> skin_moisture_ratio(const TrackingConnections& tracking, const std::vector<double>& node_moisture,
                                        double initial_moisture) {
  require_input(std::isfinite(initial_moisture) && initial_moisture > 0.0, "skin moisture", "initial moisture",
                "must be positive");
  std::vector<double> out(tracking.size(), 0.0);
  for (std::size_t i = 0; i < tracking.size(); ++i) {
    double m = 0.0;
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<std::size_t>(tracking.face_nodes[i][static_cast<std::size_t>(k)]);
      if (node >= node_moisture.size())
        throw InputError(
            "skin moisture", "tracking connection " + std::to_string(i),
            "has a face node outside the " + std::to_string(node_moisture.size()) + " node moisture values");
      m += tracking.weights[i][k] * node_moisture[node];
    }
    out[i] = std::clamp(m / initial_moisture, 0.0, 1.0);
  }
  return out;
}

}  // namespace forensim
