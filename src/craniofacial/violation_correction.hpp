#pragma once
/// Correction landmark pairs where a fitted skin and its skull still intersect (Kähler, Haber and Seidel 2003,
/// section 4.2, Figure 6a to 6b: with only the user's landmarks "some skull areas still intersect the skin", so
/// landmark pairs are added automatically, each with an interpolated tissue thickness). The cranium and
/// mandible generators (interpolated_landmarks.hpp) place pairs where they are planned; these pairs go where
/// the warp actually failed: after a warp the remaining violations (skull_skin_violations.hpp) are turned into
/// pairs that hold the skin one tissue depth off the skull there, the warp is solved again with them, and the
/// rounds repeat until none remain (TemplateFit).
///
/// Each violation gives one candidate pair:
/// - a skull vertex s outside the skin: the source is the template's rest position of the skin's closest point
///   to s (same triangle and barycentric weights), the target s + d n with n the skull's vertex normal at s;
/// - a skin vertex inside the skull: the source is that vertex's rest position, the target c + d n with c its
///   closest skull point and n the skull's interpolated vertex normal there.
/// The depth d is the smallest tissue depth among the `neighbours` given landmarks nearest to the skull point
/// (their depth vectors' lengths): the thickness of the thinnest neighbouring measurement, so a correction
/// never thickens the face beyond what the table gives nearby (the paper interpolates only where thickness is
/// near-constant; the minimum stays within the measured range where it is not). Candidates are taken
/// deepest violation first, at least `spacing_mm` apart in the template (and half that from every existing
/// source and target, which keeps the RBF systems well conditioned), at most `max_pairs` per round; the
/// spacing shrinks (to min_spacing_mm) only when no violation has a free place at the current one.

#include <cstddef>
#include <vector>

#include "core/types.hpp"
#include "craniofacial/skull_skin_violations.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct ViolationCorrectionOptions {
  int rounds = 8;              ///< warp, count, add pairs: at most this many times (0: no correction)
  std::size_t max_pairs = 64;  ///< pairs added per round
  double spacing_mm = 6.0;     ///< least distance between the new pairs' sources (template mm)...
  /// ...halved for another try (not counted as a round) while a round finds no free place, down to this: the
  /// last violations sit close to existing pairs (on headsq with the full template the last two lay within 0.5 mm
  /// of pairs already placed, and 1 mm left them).
  double min_spacing_mm = 0.25;
  std::size_t neighbours = 3;  ///< given landmarks whose smallest depth is the pair's depth
};

/// Correction pairs of one round. Entries are in the order taken (deepest violation first).
struct ViolationCorrectionPairs {
  std::vector<Vec3> sources;  ///< template skin points p (mm)
  std::vector<Vec3> skull;    ///< skull points the targets stand on (mm)
  std::vector<Vec3> normals;  ///< unit outward skull normals there
  /// The `neighbours` given landmarks nearest to each skull point (indices into the given landmarks, nearest
  /// first): the depth is re-read from them when the landmarks' depths change (TemplateFit::set_landmarks).
  std::vector<std::vector<std::size_t>> neighbours;
  std::vector<double> depth_mm;
  /// Targets skull + depth * normal (mm).
  std::vector<Vec3> targets() const;
};

/// The depth of a correction pair: the smallest |depth_vectors[i]| over `neighbours` (mm). Throws InputError for
/// an index out of range or an empty list.
double correction_depth(const std::vector<std::size_t>& neighbours, const std::vector<Vec3>& depth_vectors);

/// The pairs for `violations` between `skull` (mm, with vertex normals of its size, outward) and `warped_skin`
/// (the template skin `rest_skin` after the warp: same triangles, positions moved). `landmark_skull` and
/// `landmark_depth_vectors` are the given landmarks (mm; at least one); `existing_sources` and
/// `existing_targets` the warp's current pairs (template mm, target mm): new targets also keep half the
/// spacing from them and from each other (a second warp, such as the guides', takes them as its sources). Throws
/// InputError for meshes whose sizes disagree, a skull without vertex normals, no landmarks or bad options (spacing not
/// positive, no neighbours). Deterministic.
ViolationCorrectionPairs violation_correction_pairs(const TriMesh& skull, const TriMesh& rest_skin,
                                                    const TriMesh& warped_skin, const SkullSkinViolations& violations,
                                                    const std::vector<Vec3>& landmark_skull,
                                                    const std::vector<Vec3>& landmark_depth_vectors,
                                                    const std::vector<Vec3>& existing_sources,
                                                    const std::vector<Vec3>& existing_targets,
                                                    const ViolationCorrectionOptions& options = {});

class ClosestPointQuery;

/// violation_correction_pairs with the skull's closest-point query given (`skull_closest`, built on `skull`: a
/// SkullSkinViolationCounter's), so that successive rounds do not build it again. The same pairs.
ViolationCorrectionPairs violation_correction_pairs(
    const TriMesh& skull, const ClosestPointQuery& skull_closest, const TriMesh& rest_skin, const TriMesh& warped_skin,
    const SkullSkinViolations& violations, const std::vector<Vec3>& landmark_skull,
    const std::vector<Vec3>& landmark_depth_vectors, const std::vector<Vec3>& existing_sources,
    const std::vector<Vec3>& existing_targets, const ViolationCorrectionOptions& options = {});

}  // namespace forensim
