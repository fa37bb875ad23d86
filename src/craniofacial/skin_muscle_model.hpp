#pragma once
/// The skin-muscle-skull spring model that animates a reconstructed head (Kähler, Haber and Seidel 2003,
/// section 4.1: "a mass-spring system connecting skin, muscles, and skull, built after the head model is
/// fitted to the skull"; after Kähler et al. 2001/2002). Fixed data only (the State is a set of node
/// positions; muscle_contraction.hpp solves for it):
/// - nodes: the skin vertices first (0 .. skin_node_count-1), then every muscle fibre sample;
/// - skin springs along every skin edge and across every interior edge (joining the two opposite corners, the
///   bending resistance of the skin layer);
/// - skull springs: each skin node is held at its rest position by a zero-length spring whose stiffness falls
///   with the soft-tissue depth under it (distance to the skull): full over thin tissue (forehead, scalp,
///   nose bridge), weak over thick tissue (cheeks, lips), so skin slides where the face is mobile;
/// - fibre springs between consecutive samples of each fibre (closed rings for sphincters), two-sided (the
///   passive elasticity of the fibre; a tension-only kink at the rest length stalls Newton);
///   contraction shortens their rest length; the first sample of a linear muscle's fibre is its bony origin
///   and is fixed;
/// - attachment springs joining every fibre sample to the skin point above it (a point on a skin triangle,
///   from shape_muscles()).
/// Stiffnesses are relative (only their ratios shape the static equilibrium); lengths are mm.

#include <array>
#include <string>
#include <vector>

#include "craniofacial/muscle_layout.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct SkinMuscleModelOptions {
  double skin_stiffness = 1.0;          ///< k_s of each skin edge spring
  double bending_stiffness = 0.3;       ///< k_b of each spring across an interior edge
  double skull_stiffness = 1.0;         ///< k_bone of a skin node over thin tissue
  double loose_skull_stiffness = 0.02;  ///< k_bone over thick tissue
  double tight_depth_mm = 8.0;          ///< tissue up to this depth is held with skull_stiffness
  double loose_depth_mm = 14.0;         ///< from this depth with loose_skull_stiffness (smooth blend between)
  double fibre_stiffness = 20.0;        ///< k_m of each fibre segment
  double attachment_stiffness = 5.0;    ///< k_a joining a fibre sample to the skin above it
};

struct SkinMuscleModel {
  std::size_t skin_node_count = 0;
  std::vector<Vec3> node_rest_positions;     ///< #N, mm: skin vertices, then fibre samples
  std::vector<char> node_fixed;              ///< #N, 1 for a linear muscle's origin samples (on the bone)
  std::vector<double> node_tissue_depth_mm;  ///< #skin nodes: distance to the skull
  std::vector<double> node_skull_stiffness;  ///< #skin nodes: stiffness of the skull spring

  /// Two-node springs: skin edges, skin bending, then fibre segments.
  std::vector<std::array<Index, 2>> spring_nodes;
  std::vector<double> spring_rest_length_mm;
  std::vector<double> spring_stiffness;
  std::vector<Index> spring_muscle;  ///< muscle of a fibre segment (contracts with it), -1 for skin springs

  /// Attachments: fibre node, skin triangle corners, barycentric weights, rest offset skin point - node.
  std::vector<Index> attachment_node;
  std::vector<Tri> attachment_triangle;
  std::vector<Vec3> attachment_barycentric;
  std::vector<Vec3> attachment_offset;
  double attachment_stiffness = 0.0;

  std::vector<std::string> muscle_names;  ///< #M, in the order of the given shapes
  std::vector<MuscleKind> muscle_kinds;
};

/// Builds the model from a skin (validated, closed or open), its skull (the tissue depth of each skin vertex is
/// its distance to the nearest skull point) and the muscles shaped under that skin (shape_muscles(); each
/// skin_triangles entry must index `skin`). Deterministic. Throws InputError for an empty skin or skull,
/// muscle shapes that do not match the skin, repeated muscle names, or options out of range (stiffnesses
/// must be positive and finite, 0 < tight_depth_mm < loose_depth_mm).
SkinMuscleModel make_skin_muscle_model(const TriMesh& skin, const TriMesh& skull,
                                       const std::vector<MuscleShape>& muscles,
                                       const SkinMuscleModelOptions& options = {});

/// Stiffness of a skull spring over tissue `depth_mm` deep: skull_stiffness up to tight_depth_mm,
/// loose_skull_stiffness from loose_depth_mm, a smoothstep in log-stiffness between.
double skull_spring_stiffness(double depth_mm, const SkinMuscleModelOptions& options);

}  // namespace forensim
