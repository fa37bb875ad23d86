#pragma once
/// A body part as the desiccation system sees it (Frerichs, Vidler and Gatzidis 2020, section 4): a labelled
/// tetrahedral volume (flesh, bone) under a separate, finer skin triangle mesh, the two tied by tracking
/// connections (section 8.2), with named parts (fingers, palm; nose, ears) that results are reported by.
/// Model data: fixed during a run; positions that change live in the simulation's State.

#include <functional>
#include <string>
#include <vector>

#include "body/tracking.hpp"
#include "core/types.hpp"
#include "geometry/tet_boundary.hpp"
#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Part index of a point (mm), e.g. Phantom::part_at; must return an index into the part names.
using PartFunction = std::function<int(const Vec3&)>;

/// How a body part lay and how to look at it, in the model's frame: the views that fit it, its up (superior,
/// or the back of the hand for a limb lying palm down) and front for pictures, and the direction of gravity as
/// it lay after death, which livor mortis settles the blood along and the ground lies across.
struct BodyPose {
  std::string views = "arm";      ///< picture layout: "arm" (views of a limb along +x) or "head"
  Vec3 up = Vec3::UnitZ();        ///< unit direction drawn upwards in pictures
  Vec3 front = Vec3::UnitY();     ///< unit direction facing the viewer in front views (orthogonal to up)
  Vec3 gravity = -Vec3::UnitZ();  ///< unit direction of gravity as the body lay (livor mortis, ground contact)

  /// The pose of a built-in phantom ("arm": palm down along +x, thumb +y; "head": z up, facing -y, upright).
  static BodyPose of_phantom(const std::string& phantom);
  /// Checks the names and that the vectors are finite unit vectors, up orthogonal to front; throws InputError
  /// naming `source`.
  void validate(const std::string& source) const;
};

struct BodyModel {
  TetMesh volume;                       ///< rest volume, tets labelled by TissueLabel
  TriMesh skin;                         ///< rest skin, #S vertices
  std::vector<TetFace> boundary_faces;  ///< tet_boundary_faces(volume): the faces tracking points lie on
  TrackingConnections tracking;         ///< #S, one per skin vertex
  std::vector<std::string> part_names;  ///< names indexed by the part indices below (may be empty)
  std::vector<int> skin_vertex_parts;   ///< #S part index of each skin vertex, or empty
  std::vector<int> tet_parts;           ///< #T part index of each tet (at its centroid), or empty
  BodyPose pose;                        ///< how it lay and how to look at it

  /// Checks the meshes, that boundary_faces is the volume's boundary (#faces and node triples, in
  /// tet_boundary_faces order), the tracking connections (sizes, ranges, weights, and that each
  /// connection's face nodes are those of its boundary face), the pose, and the part arrays (sizes and indices in
  /// [0, #part_names)). Throws InputError naming `source` and the first bad item.
  void validate(const std::string& source) const;
};

/// Assembles a body model: computes the volume's boundary faces and the tracking connections of `skin`
/// (compute_tracking with `options`), and, when `part_at` is given, the part of every skin vertex and of
/// every tet's centroid. Throws InputError for invalid meshes or a part index outside [0, #part_names).
BodyModel make_body_model(TetMesh volume, TriMesh skin, std::vector<std::string> part_names = {},
                          const PartFunction& part_at = {}, const TrackingOptions& options = {});

/// Fills model.part_names, skin_vertex_parts and tet_parts from `part_at` (evaluated at skin vertices and
/// tet centroids, in parallel). Throws InputError when part_at returns an index outside [0, #part_names).
void assign_parts(BodyModel& model, std::vector<std::string> part_names, const PartFunction& part_at);

}  // namespace forensim
