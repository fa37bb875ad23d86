#pragma once
/// Registration of a reference skull onto a target skull, the first step of automatic landmark placement
/// (issue 8: "registering a reference skull that carries landmarks to the target skull, similarity then
/// non-rigid"). Kahler et al. (2003, section 3) place landmarks by hand; forensim places them by carrying a
/// reference skull's landmarks across this registration and refining them (landmark_detection.hpp).
///
/// Two stages, both iterated closest points against the target's surface (src/spatial ClosestPointQuery):
/// 1. a similarity x -> s R x + t (scaled ICP, point-to-plane with a weak point-to-point term, the worst pairs
///    trimmed), started from the principal axes of both meshes (all four proper sign choices) and from the
///    meshes' own orientation, the best trimmed RMS kept;
/// 2. a smooth displacement u(y) = sum_j w_j exp(-|y - c_j|^2 / (2 sigma^2)) on coarse nodes c_j spread over the
///    reference (Gaussian radial basis functions), fitted by regularised least squares
///    min sum_i |P_i (y_i + u(y_i) - q_i)|^2 + lambda w^T K w, K_jk = exp(-|c_j - c_k|^2 / (2 sigma^2)),
///    with the stiffness lambda lowered stage by stage (the motion-coherence prior of coherent point drift,
///    Myronenko and Song 2010, with closest-point correspondences).
/// Deterministic at any thread count: closest-point batches keep their order and every reduction is serial
/// or over fixed blocks.

#include <cstddef>
#include <vector>

#include "core/types.hpp"
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
  std::size_t max_samples = 4000;     ///< reference vertices used (every k-th when the mesh has more)
  int max_iterations = 80;            ///< Gauss-Newton iterations per start
  double trim_fraction = 0.1;         ///< share of worst pairs dropped each iteration (missing parts, damage)
  double point_weight = 0.1;          ///< weight of the point-to-point term beside point-to-plane (stabilises sliding)
  double tolerance = 1e-5;            ///< stop when the update (rotation rad, log scale, translation / size) is below
  bool principal_axis_starts = true;  ///< also start from the four proper principal-axis alignments
};

struct NonRigidRegistrationOptions {
  std::size_t node_count = 120;  ///< coarse nodes c_j (farthest-point samples of the reference samples)
  double kernel_width = 1.5;     ///< sigma as a multiple of the mean nearest-node spacing
  /// lambda per stage, relative to trace(A^T A) / trace(K) (scale free); the last is the final smoothness.
  std::vector<double> stiffness_schedule = {1.0, 0.1, 0.01, 0.001};
  int iterations_per_stage = 8;
  double trim_fraction = 0.1;      ///< share of worst pairs dropped each iteration
  double tangential_weight = 0.2;  ///< weight of the tangential part of each closest-point offset (lets it slide)
};

struct SkullRegistrationOptions {
  SimilarityRegistrationOptions similarity;
  NonRigidRegistrationOptions non_rigid;
  bool non_rigid_enabled = true;
};

/// The reference -> target map and how well it fits.
struct SkullRegistration {
  Similarity similarity;
  std::vector<Vec3> node_positions;        ///< #N nodes c_j in target space (similarity-mapped reference), mm
  std::vector<Vec3> node_weights;          ///< #N coefficients w_j, mm
  double kernel_width_mm = 0.0;            ///< sigma
  double similarity_rms_mm = 0.0;          ///< trimmed RMS point-to-surface distance after the similarity
  double rms_mm = 0.0;                     ///< trimmed RMS after the non-rigid stage (= similarity_rms_mm without it)
  int similarity_iterations = 0;           ///< iterations of the start that was kept
  std::vector<Vec3> sample_positions;      ///< #S reference sample points mapped into target space, mm
  std::vector<double> sample_residual_mm;  ///< #S distance of each mapped sample to the target surface, mm

  /// Target-space position of a reference point: the similarity, then the displacement field.
  Vec3 map(const Vec3& reference_point) const;
  /// Displacement field u at target-space point y (zero without the non-rigid stage), mm.
  Vec3 displacement(const Vec3& y) const;
  /// RMS of sample_residual_mm over the samples mapped within `radius_mm` of `target_point` (the global
  /// rms_mm when none is), mm: how well the registration fits near a landmark.
  double local_residual_mm(const Vec3& target_point, double radius_mm) const;
};

/// Similarity that maps `reference` onto `target` (stage 1). Throws InputError naming "reference skull" or
/// "target skull" when a mesh has no triangles or fewer than 4 vertices, or its bounding box is degenerate.
/// `rms_mm` and `iterations` receive the trimmed RMS and the iterations of the start kept, when not null.
Similarity register_similarity(const TriMesh& reference, const TriMesh& target,
                               const SimilarityRegistrationOptions& options = {}, double* rms_mm = nullptr,
                               int* iterations = nullptr);

/// Similarity then non-rigid registration of `reference` onto `target` (both mm). Throws InputError as
/// register_similarity, and for options out of range (naming the option).
SkullRegistration register_skull(const TriMesh& reference, const TriMesh& target,
                                 const SkullRegistrationOptions& options = {});

}  // namespace forensim
