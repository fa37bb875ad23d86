#pragma once
/// The wrinkling skin of the desiccation system (Frerichs, Vidler and Gatzidis 2020, sections 8.1 and 8.2):
/// position-based dynamics (Mueller et al. 2007, Algorithm 1) on the skin triangle mesh, pulled along by the
/// shrinking tet volume through tracking constraints. Per step:
///  1. tracking points t_i from the current volume node positions (the stored tracking connections), the
///     tracking stiffness k_j from the skin's moisture (slippage, eq. 35) and the stretch and bending
///     stiffness from it (dry skin is stiffer: it turns leathery);
///  2. v += dt w f_ext; for inward-facing connections farther than the slip radius r_j from their anchor (the
///     tracking point plus the vertex's rest offset from it, so r_j is the lift-off from the volume's surface),
///     the pulling correction of eq. 34 with stiffness k_j is added to the velocity. r_j = (1 - k_j / k_t) r_max
///     (eq. 33, skin_slippage.hpp) is 0 for wet skin and opens to r_max as the skin dries and k_j falls (eq. 35);
///  3. velocity damping (k_damping; by default of the skin's velocity relative to its tracking point's, see
///     velocity_damping.hpp), predicted positions p = x + dt v;
///  4. collision constraints against the deforming volume boundary for the predicted positions;
///  5. Gauss-Seidel iterations: stretch constraints (per edge), bending constraints (per edge-adjacent triangle
///     pair), one-sided attachments of the outward-facing connections (stiffness 1, constant radius), of the
///     inward-facing ones (stiffness k_j, radius r_j; SkinSettings::hold_inward), the bound of every inward-facing
///     one at r_max ("the maximum radius a vertex is allowed to move away from the volume boundary", section 8.2:
///     stiffness 1, also for slipped skin, whose k_j is 0) and the collision planes. Stretch and
///     bending constraints are projected by independent groups (graph colouring) in parallel, so the result does not
///     depend on the thread count;
///  6. v = (p - x) / dt, x = p.
///
/// Model (rest skin, constraints with their rest data, tracking, collision candidates) is apart from State
/// (positions, velocities). Lengths in mm, time in s, moisture as a ratio of the initial moisture in [0, 1].

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"
#include "pbd/bending_constraint.hpp"
#include "pbd/constraint_coloring.hpp"
#include "pbd/skin_slippage.hpp"
#include "pbd/stretch_constraint.hpp"

namespace forensim {

/// The paper's wrinkle controls (section 8.2, Figure 8): the maximum tracking radius r_max and the velocity
/// damping k_damping. Figure 8's r_max values (0.001, 0.002, 0.004) are read as fractions of the model's size,
/// the largest side of the rest skin's bounding box (the paper's models are about a unit long), so a set
/// behaves alike on an arm in mm and a head in mm.
struct WrinkleControls {
  double r_max_relative = 0.002;  ///< r_max / model size
  double damping = 0.2;           ///< k_damping in [0, 1]
  /// Figure 8's sets: 0 (0.001, 0.5) little wrinkling, 1 (0.002, 0.2), 2 (0.004, 0.08) strong wrinkles.
  /// Throws InputError for another index.
  static WrinkleControls figure8(int set);
};

/// What the skin's velocity is damped towards.
enum class DampingFrame {
  volume,        ///< the velocity of the vertex's tracking point: the skin keeps the body's motion
  rigid_motion,  ///< Mueller et al. 2007 section 3.5: the rigid motion of the whole skin
};

struct SkinSettings {
  WrinkleControls wrinkle;
  DampingFrame damping_frame = DampingFrame::volume;
  SlippageLaw slippage;  ///< tracking stiffness k_t and the thresholds of eq. 35
  int iterations = 8;    ///< Gauss-Seidel iterations per step
  /// Bending constraints are projected on every bending_interval-th iteration only (the last included), with
  /// the per-iteration stiffness of that many passes (an interval above `iterations` acts as `iterations`): bending is
  /// the costliest projection and the skin's bending stiffness is low, so fewer passes hold it about as well. 1
  /// projects it on every iteration.
  int bending_interval = 2;
  double stretch_stiffness_wet = 0.3;  ///< stretch stiffness of fresh skin (moisture ratio 1), in [0, 1]
  double stretch_stiffness_dry = 0.8;  ///< ... of fully dried skin (ratio 0): leathery
  /// Fraction by which the skin's edges shorten when fully dried ("the skin compresses due to water loss",
  /// section 8): rest lengths d (1 - s (1 - m)) for an edge of moisture ratio m.
  double skin_shrinkage = 0.15;
  /// Also project the inward-facing tracking constraints in the Gauss-Seidel loop (stiffness k_j, radius r_j),
  /// as Mueller and Chentanez's attachments, besides their pulling correction (without it the stretch
  /// constraints, projected after the pull, undo most of it). The bound at r_max is projected either way.
  bool hold_inward = true;
  double bending_stiffness_wet = 0.02;
  double bending_stiffness_dry = 0.1;
  Vec3 gravity_mm_per_s2 = Vec3::Zero();  ///< f_ext per unit mass (0: the volume alone moves the skin)
  /// Throws InputError naming `source` (and the setting) for a value out of range.
  void validate(const std::string& source) const;
};

/// Fixed data of a skin simulation (flat arrays: #S skin vertices, #E edges, #B bending pairs, #F volume
/// boundary faces).
struct SkinModel {
  SkinSettings settings;
  std::vector<Vec3> vertex_rest_position;           ///< #S rest skin (mm)
  std::vector<Tri> triangles;                       ///< skin triangles
  std::vector<double> vertex_inverse_mass;          ///< #S w_i: lumped skin area, normalised to mean mass 1
  StretchConstraints stretch;                       ///< #E
  BendingConstraints bending;                       ///< #B
  ConstraintGroups stretch_groups, bending_groups;  ///< independent groups (colouring)
  TrackingConnections tracking;                     ///< #S, from the body model
  /// #S rest offset of each skin vertex from its tracking point (mm, p_i - t_i on the rest body): an
  /// inward-facing connection holds the vertex within r_j (pulled) and r_max (bound) of its anchor t_i +
  /// offset_i, so r_max bounds how far the skin slides and lifts off the volume. (The offset is not rotated with the
  /// volume: the volume's local rotations under shrinkage are small.)
  std::vector<Vec3> vertex_tracking_offset;
  std::vector<Tri> boundary_face_nodes;  ///< #F volume-node triples of the boundary faces (outward)
  /// Collision candidates of vertex i: boundary faces vertex_collision_faces[offsets[i] .. offsets[i+1]) (the
  /// tracking face and the faces sharing a node with it).
  std::vector<Index> vertex_collision_offsets, vertex_collision_faces;
  std::vector<double> vertex_collision_floor;  ///< #S allowed height over the boundary: min(0, rest height)
  std::size_t volume_node_count = 0;
  double model_size_mm = 0.0;  ///< largest side of the rest skin's bounding box
  double r_max_mm = 0.0;       ///< wrinkle.r_max_relative * model_size_mm
  double mean_edge_mm = 0.0;   ///< mean rest edge length
  std::size_t vertex_count() const { return vertex_rest_position.size(); }
};

/// Builds the skin model of a body model (validated, InputError naming "body model"): constraints on the rest
/// skin, their colouring, the tracking connections and the collision candidates. Throws InputError for bad
/// settings.
SkinModel make_skin_model(const BodyModel& body, const SkinSettings& settings = {});

/// Time-varying data of a skin simulation.
struct SkinState {
  std::vector<Vec3> positions;        ///< #S (mm)
  std::vector<Vec3> velocities;       ///< #S (mm/s)
  std::vector<Vec3> tracking_points;  ///< #S t_i of the last step (mm; empty before the first step)
  double time_s = 0.0;
  long long step_count = 0;
};

/// The rest skin at rest.
SkinState initial_skin_state(const SkinModel& model);

/// What one step did.
struct SkinStepReport {
  std::size_t pulled = 0;               ///< inward-facing connections beyond r_j that pulled (eq. 34)
  std::size_t attached = 0;             ///< outward-facing connections (one-sided attachments)
  std::size_t slipped = 0;              ///< connections with zero stiffness (eq. 35)
  std::size_t collisions = 0;           ///< collision constraints generated
  double max_tracking_excess_mm = 0.0;  ///< max over attached vertices of |t - p| - r_j after the step
  double seconds = 0.0;
};

/// Setup-once, step-many skin solver (keeps scratch buffers; the model is kept by reference). The constructor
/// lays the stretch and bending constraints out colour by colour in flat arrays (vertex indices, rest data),
/// so each Gauss-Seidel pass over a colour streams through contiguous memory.
class SkinSimulation {
 public:
  explicit SkinSimulation(const SkinModel& model);

  /// One step of dt_s seconds (> 0) with the volume at `volume_node_positions` (#V of the body's volume, mm)
  /// and the skin's moisture `vertex_moisture_ratio` (#S, current / initial, clamped to [0, 1]). Throws
  /// InputError for wrong sizes or a bad dt, NumericError when a position turns non-finite.
  SkinStepReport step(SkinState& state, const std::vector<Vec3>& volume_node_positions,
                      const std::vector<double>& vertex_moisture_ratio, double dt_s);

 private:
  const SkinModel& m_model;
  std::vector<Vec3> m_tracking_points, m_anchors, m_frame_velocities, m_face_normals, m_predicted, m_plane_points,
      m_plane_normals;
  std::vector<double> m_tracking_stiffness, m_tracking_pass_stiffness, m_edge_stiffness, m_edge_rest_length,
      m_pair_stiffness, m_attach_radius;
  std::vector<double> m_moisture, m_stiffness_moisture;  ///< clamped moisture of this step, of the stiffness above
  std::vector<std::uint8_t> m_outward, m_has_plane, m_pulled;
  // Constraints in colour order: slot s of colour c lies in [offsets[c], offsets[c + 1]).
  std::vector<std::size_t> m_stretch_offsets, m_bending_offsets;
  std::vector<std::array<std::uint32_t, 2>> m_stretch_vertices;  ///< per slot
  std::vector<double> m_stretch_rest;                            ///< per slot, model rest length
  std::vector<std::array<std::uint32_t, 4>> m_bending_vertices;  ///< per slot
  std::vector<double> m_bending_rest;                            ///< per slot, rest angle
};

/// Moisture ratio of every skin vertex: the node moisture interpolated at the tracking point (the
/// connection's face nodes and weights) over `initial_moisture` (> 0), clamped to [0, 1].
std::vector<double> skin_moisture_ratio(const TrackingConnections& tracking, const std::vector<double>& node_moisture,
                                        double initial_moisture);

}  // namespace forensim
