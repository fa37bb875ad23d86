#pragma once
/// Automatic skull landmarks (issue 8): a reference skull's landmarks are carried onto the target skull through
/// skull_registration, then each is refined by its geometric definition in the target's head frame (Frankfort
/// horizontal, midsagittal plane; head_frame.hpp) and given a confidence. Definitions follow the vocabulary
/// (landmark_vocabulary.hpp, after Caple and Stephan 2016; reference: shared/reference/tissue-depth.md):
/// "most anterior point of the chin" becomes the vertex of largest anterior coordinate within a search radius of
/// the transferred point; for midline sites the candidates are the points of the skull's midsagittal profile
/// (where mesh edges cross the midsagittal plane), so midline landmarks lie exactly in the plane.

#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "craniofacial/head_frame.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "craniofacial/skull_registration.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// How a site is refined once transferred.
enum class LandmarkRule {
  transfer,  ///< kept where the registration put it (on the surface): sutures, foramina, rims
  midline,   ///< moved onto the surface's intersection with the midsagittal plane
  extremal,  ///< the most extreme surface point along a head-frame direction, within the search radius
};

/// The geometric definition of one site.
struct LandmarkDefinition {
  std::string site;  ///< vocabulary abbreviation ("pg", "zy")
  LandmarkRule rule = LandmarkRule::transfer;
  bool midline = false;                ///< restricted to the midsagittal profile (midline sites)
  Vec3 direction_head = Vec3::Zero();  ///< extremal: unit direction in head coordinates (LPS), left side for pairs
  double search_radius_mm = 10.0;      ///< how far refinement may move the transferred point
};

/// The built-in definitions (vertex +z, opisthocranion +y, glabella and pogonion -y, menton -z, gnathion the
/// anterior-inferior bisector, nasion and subspinale the deepest (+y) midline point, zygion and gonion lateral, ...).
const std::vector<LandmarkDefinition>& landmark_definitions();
/// Definition of a landmark name (any accepted spelling, side suffix allowed), or nullopt when it has none.
std::optional<LandmarkDefinition> landmark_definition(const std::string& landmark_name);

struct LandmarkDetectionOptions {
  SkullRegistrationOptions registration;
  SymmetryPlaneOptions symmetry;           ///< target's midsagittal plane (fitted to the skull)
  double residual_radius_mm = 15.0;        ///< neighbourhood of the local registration residual
  double residual_scale_mm = 1.5;          ///< residual at which the residual term of the confidence is 1/2
  double symmetry_scale_mm = 4.0;          ///< left/right or off-plane disagreement at which that term is 1/2
  double transfer_definition_score = 0.6;  ///< definition term of sites refined by transfer only
  /// The scan shows no nasal bones when the midsagittal segment from the refined nasion to the refined rhinion
  /// runs farther than this from the skull at some point (a CT too coarse for the thin nasal bones: rhinion is then
  /// found on the maxilla below the aperture and the segment crosses the opening); mn and rhi are left out
  /// (LandmarkDetection::left_out), since the bone they are measured from is missing. 0 = never.
  double nasal_bone_gap_mm = 4.0;
};

/// Distance of the farthest of nine points spread along the segment from `nasion` to `rhinion` (at 0.1, 0.2, ...,
/// 0.9) to the nearest vertex of `mesh`, mm: small where the nasal bones join the two, large where the segment
/// crosses the nasal aperture. Throws InputError for a mesh without vertices.
double nasal_bone_gap_mm(const TriMesh& mesh, const Vec3& nasion, const Vec3& rhinion);

/// Refinement of one landmark by its definition.
struct RefinedLandmark {
  Vec3 position_mm = Vec3::Zero();
  double sharpness = 0.0;        ///< in [0, 1]: how clearly the definition picks this point (1 = sharp extremum)
  bool at_search_limit = false;  ///< the extremum lay at the edge of the search ball (not a local extremum)
};

/// Refines `start` on `mesh` by `definition` in `frame` (its midsagittal plane and axes; a right-side landmark
/// mirrors the direction's x). Extremal: the candidate maximising direction . p within the search radius (ties to
/// the first); candidates are vertices, or profile points for midline sites; sharpness d / (d + 0.02 radius) from
/// the smallest height drop d over the ring at 0.5-1 radius around it, halved at the search limit. Midline: the
/// profile point closest to the start's projection onto the plane. Transfer: the closest vertex, sharpness 0.
/// Candidates are vertices whose normal agrees with the normal at the start (cos > 0.3), so the inner table of a
/// CT skull or the inside of a thin bone never wins. Vertex normals are computed when `mesh` has none.
RefinedLandmark refine_landmark(const TriMesh& mesh, const HeadFrame& frame, const LandmarkDefinition& definition,
                                Side side, const Vec3& start);

/// Per-landmark account of a detection.
struct DetectedLandmark {
  std::string name;
  LandmarkRule rule = LandmarkRule::transfer;
  Vec3 transferred_mm = Vec3::Zero();  ///< reference landmark through the registration
  Vec3 refined_mm = Vec3::Zero();      ///< final position
  double residual_mm = 0.0;            ///< local registration residual
  double sharpness = 0.0;              ///< definition term
  double symmetry_error_mm = 0.0;      ///< |mirror(left) - right| for pairs, distance off the plane for midline sites
  double confidence = 0.0;             ///< geometric mean of the residual, definition and symmetry terms
  /// False when the transferred point lies outside the target's field of view (a CT's cut-off vault): the
  /// landmark stays at transferred_mm, on the registered reference, with definition term and confidence 0.
  bool in_view = true;
};

/// Result of detect_landmarks.
struct LandmarkDetection {
  LandmarkSet landmarks;                  ///< source detected, confidence per landmark
  std::vector<DetectedLandmark> details;  ///< same order as landmarks
  /// Reference landmarks not placed, each with the reason ("mn": "the scan shows no nasal bones ...").
  std::vector<std::pair<std::string, std::string>> left_out;
  SkullRegistration registration;
  HeadFrame frame;  ///< the target's head frame
};

/// Places `reference_landmarks` (on `reference`) onto `target`: register_skull, transfer every landmark, fit the
/// target's head frame (Frankfort plane of the transferred po_L, po_R, or_L or or_R; midsagittal plane fitted to
/// the target), refine each landmark by its definition, then score it. Confidence = (c_res c_def c_sym)^(1/3) with
/// c_res = 1 / (1 + (residual / residual_scale)^2), c_def the sharpness (transfer_definition_score for transfer
/// sites) and c_sym = 1 / (1 + (symmetry error / symmetry_scale)^2). Landmarks transferred outside
/// options.registration.similarity.target_view are not refined (DetectedLandmark::in_view). Where the target shows no
/// nasal bones (LandmarkDetectionOptions::nasal_bone_gap_mm), mn and rhi are left out. Throws InputError naming
/// "reference landmarks" when the set is empty or lacks the Frankfort landmarks, and the registration's errors.
LandmarkDetection detect_landmarks(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                   const TriMesh& target, const LandmarkDetectionOptions& options = {});

/// As detect_landmarks, for a reference without the Frankfort landmarks: the registration keeps the reference
/// frame's midsagittal plane on the target's symmetry plane (SimilarityRegistrationOptions::reference_midsagittal,
/// unless the options give one); the target's frame is `reference_frame` carried through the similarity, its
/// midsagittal plane refitted to the target (fit_symmetry_plane). Throws InputError naming "reference landmarks" when
/// the set is empty.
LandmarkDetection detect_landmarks(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                   const HeadFrame& reference_frame, const TriMesh& target,
                                   const LandmarkDetectionOptions& options = {});

/// Refines every landmark of `rough` (roughly placed on `mesh`) by its definition in `frame` without
/// registration: for building a reference skull's landmarks from rough guesses. Same order and names; source
/// detected, confidence the definition term.
LandmarkSet refine_landmarks(const TriMesh& mesh, const HeadFrame& frame, const LandmarkSet& rough);

/// Landmarks located on a skull by their definitions alone, without a reference: global extrema of the skull in
/// `frame` within regions given as shares of the skull's height H (head z) and depth (head y): vertex (highest
/// profile point), opisthocranion (most posterior profile point), glabella (most anterior profile point above
/// 0.55 H), pogonion, gnathion and menton (most anterior, anterior-inferior and lowest profile points below 0.2 H
/// in the anterior half), zygia (most lateral points between 0.35 and 0.6 H in the anterior half), gonia (the
/// gonion direction below 0.3 H in the posterior three quarters); then refine_landmarks repeated until
/// no point moves (at most 11 rounds), so each is a local extremum. For building a reference
/// skull's landmarks when no landmarked reference exists. Throws InputError for a mesh without triangles.
LandmarkSet locate_landmarks(const TriMesh& skull, const HeadFrame& frame);

std::string to_string(LandmarkRule rule);

}  // namespace forensim
