#pragma once
/// Registration of a reference skull onto a target skull, the first step of automatic landmark placement
/// (issue 8: "registering a reference skull that carries landmarks to the target skull, similarity then
/// non-rigid"). Kahler et al. (2003, section 3) place landmarks by hand; forensim places them by carrying a
/// reference skull's landmarks across this registration and refining them (landmark_detection.hpp).
///
/// Two stages, both iterated closest points against the target's surface (src/spatial ClosestPointQuery):
/// 1. a similarity x -> s R x + t (scaled ICP, point-to-plane with a weak point-to-point term, the worst pairs
///    trimmed), started from the principal axes of both meshes (all four proper sign choices) and from the
///    meshes' own orientation and its axis-aligned quarter turns (scans and CTs are mostly taken square to the
///    head), at scale 1 under a Gaussian prior on log scale (both meshes in mm; MAP steps), each briefly, the
///    best further; then one candidate per basin (distinct rotations) on more samples, ranked by the RMS of its
///    reference -> target pairs (the two-way RMS on few samples cannot tell a pitched skull from the right pose),
///    the best run to convergence on all samples. The pairs run both ways, so that a partial target
///    does not shrink the reference into itself (one-way ICP with a free scale always gains by shrinking):
///    reference samples to their closest target points, kept only where the target has data (inside its
///    field of view, not on a cap closing a cut: scan_field_of_view.hpp), and target samples to their closest
///    reference points, the worst share trimmed (parts the reference lacks: vertebrae, the CT table). Each
///    direction is a trimmed ICP (Chetverikov et al. 2002); together they are the symmetric ICP of partial
///    overlaps;
/// 2. a smooth displacement u(y) = sum_j w_j exp(-|y - c_j|^2 / (2 sigma^2)) on coarse nodes c_j spread over the
///    reference (Gaussian radial basis functions), fitted by regularised least squares
///    min sum_i |P_i (y_i + u(y_i) - q_i)|^2 + lambda w^T K w, K_jk = exp(-|c_j - c_k|^2 / (2 sigma^2)),
///    with the stiffness lambda lowered stage by stage (the motion-coherence prior of coherent point drift,
///    Myronenko and Song 2010, with closest-point correspondences); reference samples outside the target's field
///    of view have no pair and follow the smooth field. The pairs again run both ways: beside each reference
///    sample's closest target point, each target sample pulls its nearest moving reference sample towards its
///    tangent plane (surfaces facing the same way only, the worst share trimmed: vertebrae, the hyoid). One way
///    only, a part the target has longer (a lower chin) is never reached: the reference's closest points slide
///    along the part's side instead, and where they stop depends on the reference's sampling (the coarse and
///    the full template's menton landed 8 mm apart on headsq; with the reverse pairs about 1 mm).
/// The final run stops at the noise floor of its trimmed pairs (SimilarityRegistrationOptions::stall_iterations)
/// and keeps its lowest-RMS iterate. Every iteration's closest-point searches are bounded by the distance to the
/// previous iteration's closest points (ClosestPointQuery::query_batch_bounded: same answers, found sooner).
/// Deterministic at any thread count: closest-point batches keep their order and every reduction is serial
/// or over fixed blocks.

#include <cstddef>
#include <optional>
#include <vector>

#include "core/types.hpp"
#include "craniofacial/head_frame.hpp"
#include "craniofacial/scan_field_of_view.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// x -> scale * rotation * x + translation.
struct Similarity {
  double scale = 1.0;
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return scale * (rotation * x) + translation; }
  /// The map as an affine transform.
  Eigen::Affine3d affine() const;
};

struct SimilarityRegistrationOptions {
  std::size_t max_samples =
      4000;                 ///< reference vertices used (every k-th when the mesh has more); half as many target ones
  int max_iterations = 80;  ///< Gauss-Newton iterations per start
  double trim_fraction = 0.1;  ///< share of worst pairs dropped each iteration (missing parts, damage)
  double point_weight = 0.1;   ///< weight of the point-to-point term beside point-to-plane (stabilises sliding)
  double tolerance = 1e-7;     ///< stop when the update (rotation rad, log scale, translation / size) is below
  /// Also stop when the trimmed RMS has not fallen by a relative stall_tolerance for stall_iterations iterations
  /// (0: never) in the final run on all samples: trimming flips the kept pairs at the optimum, so the steps hover
  /// above the tolerance. That run keeps its lowest-RMS iterate.
  int stall_iterations = 8;
  /// Starts that are run on all samples after the brief runs (the best by their RMS); the one whose
  /// reference -> target pairs fit best is kept.
  std::size_t final_candidates = 1;
  /// Distinct basins (rotations more than basin_angle_deg apart) among the brief runs' best, each carried through
  /// basin_iterations on basin_samples reference samples and ranked by the RMS of its reference -> target pairs
  /// (the skull-to-target fit); the best goes on to the final run. On few samples the two-way RMS cannot tell a
  /// skull pitched about its plane's normal from the right pose (the reverse pairs also count parts the reference
  /// lacks), while the reference -> target pairs on more samples can. 1: the two-way RMS alone decides.
  std::size_t basin_candidates = 4;
  /// Brief runs carried refine_iterations further on few samples before the basins are told apart, best first: on
  /// headsq the full template's right basin starts from the 9th to 12th best brief run.
  std::size_t refined_starts = 24;
  int refine_iterations = 12;
  double basin_angle_deg = 10.0;
  std::size_t basin_samples = 1000;
  int basin_iterations = 20;
  double stall_tolerance = 1e-4;
  bool principal_axis_starts = true;  ///< also start from the four proper principal-axis alignments
  bool quarter_turn_starts = true;    ///< also start from the 23 other axis-aligned proper rotations
  /// Weight of the target -> reference pairs beside the reference -> target ones (0: one way only).
  double reverse_weight = 1.0;
  double reverse_trim_fraction = 0.3;  ///< share of worst target -> reference pairs dropped
  /// SD of a Gaussian prior on log(scale) about 0 (both skulls in mm; adult skulls vary by about 10 %); 0 = none.
  /// The starts take scale 1 with the prior, the moment-matched scale without.
  double scale_prior_sd = 0.1;
  /// Where the target has data (a CT's lattice; unbounded for meshes): reference samples outside it, or whose
  /// closest target point lies on a cap, have no pair. Used by the non-rigid stage too.
  ScanFieldOfView target_view;
  /// The reference's plane of bilateral symmetry (refined by fit_symmetry_plane). When given, the target's is fitted
  /// (fit_symmetry_plane from the planes through its centroid square to the coordinate and principal axes, the lowest
  /// RMS kept) and the similarity maps the one onto the other: only the turn about the plane's normal, the scale and
  /// the shift within the plane stay free, started every 30 degrees of the turn, both ways round. This keeps a
  /// reference of a different shape (the template phantom) from settling turned sideways on a partial skull.
  std::optional<Plane> reference_midsagittal;
};

struct NonRigidRegistrationOptions {
  std::size_t node_count = 120;  ///< coarse nodes c_j (farthest-point samples of the reference samples)
  double kernel_width = 1.5;     ///< sigma as a multiple of the mean nearest-node spacing
  /// lambda per stage, relative to trace(A^T A) / trace(K) (scale free); the last is the final smoothness.
  std::vector<double> stiffness_schedule = {1.0, 0.1, 0.01, 0.001};
  int iterations_per_stage = 8;
  double trim_fraction = 0.1;      ///< share of worst pairs dropped each iteration
  double tangential_weight = 0.2;  ///< weight of the tangential part of each closest-point offset (lets it slide)
  /// Weight of the reverse pairs (target samples to their nearest moving reference sample) beside the forward ones
  /// (0: forward pairs only, which cannot pull the reference out along a part the target has longer).
  double reverse_weight = 1.0;
  double reverse_trim_fraction = 0.3;  ///< share of worst reverse pairs dropped (parts the reference lacks)
  /// A reverse pair needs the two surfaces' normals within acos(reverse_normal_cos) of each other.
  double reverse_normal_cos = 0.5;
};

struct SkullRegistrationOptions {
  SimilarityRegistrationOptions similarity;
  NonRigidRegistrationOptions non_rigid;
  bool non_rigid_enabled = true;
};

/// The reference -> target map and how well it fits.
struct SkullRegistration {
  Similarity similarity;
  std::vector<Vec3> node_positions;         ///< #N nodes c_j in target space (similarity-mapped reference), mm
  std::vector<Vec3> node_weights;           ///< #N coefficients w_j, mm
  double kernel_width_mm = 0.0;             ///< sigma
  double similarity_rms_mm = 0.0;           ///< trimmed RMS reference -> target distance after the similarity
  double rms_mm = 0.0;                      ///< trimmed RMS after the non-rigid stage (= similarity_rms_mm without it)
  int similarity_iterations = 0;            ///< iterations of the start that was kept
  std::vector<Vec3> sample_positions;       ///< #S reference sample points mapped into target space, mm
  std::vector<double> sample_residual_mm;   ///< #S distance of each mapped sample to the target surface, mm
  std::vector<char> sample_in_view;         ///< #S 1 where the sample has a pair (in the target's field of view)
  std::optional<Plane> target_midsagittal;  ///< the target's fitted symmetry plane (with reference_midsagittal)

  /// Target-space position of a reference point: the similarity, then the displacement field.
  Vec3 map(const Vec3& reference_point) const;
  /// Displacement field u at target-space point y (zero without the non-rigid stage), mm.
  Vec3 displacement(const Vec3& y) const;
  /// RMS of sample_residual_mm over the samples in view mapped within `radius_mm` of `target_point` (the global
  /// rms_mm when none is), mm: how well the registration fits near a landmark.
  double local_residual_mm(const Vec3& target_point, double radius_mm) const;
};

/// Similarity that maps `reference` onto `target` (stage 1). Throws InputError naming "reference skull" or
/// "target skull" when a mesh has no triangles or fewer than 4 vertices, or its bounding box is degenerate.
/// `rms_mm` and `iterations` receive the trimmed RMS and the iterations of the start kept, when not null.
Similarity register_similarity(const TriMesh& reference, const TriMesh& target,
                               const SimilarityRegistrationOptions& options = {}, double* rms_mm = nullptr,
                               int* iterations = nullptr);

/// Angle of the rotation a^T b that takes rotation a onto rotation b, degrees in [0, 180].
double rotation_angle_deg(const Mat3& a, const Mat3& b);

/// Indices into `ranked` (similarities, best first) of the first of each basin: a similarity whose rotation lies
/// within `angle_deg` of an earlier kept one's belongs to that one's basin. At most `max_count`, in rank order.
/// Throws InputError for a negative angle.
std::vector<std::size_t> distinct_basins(const std::vector<Similarity>& ranked, double angle_deg,
                                         std::size_t max_count);

/// The target's plane of symmetry as register_similarity finds it with reference_midsagittal: fit_symmetry_plane
/// from the planes through the centroid square to the coordinate and principal axes, the lowest RMS kept.
SymmetryPlaneFit fit_target_symmetry(const TriMesh& target);

/// Similarity then non-rigid registration of `reference` onto `target` (both mm). Throws InputError as
/// register_similarity, and for options out of range (naming the option).
SkullRegistration register_skull(const TriMesh& reference, const TriMesh& target,
                                 const SkullRegistrationOptions& options = {});

}  // namespace forensim
