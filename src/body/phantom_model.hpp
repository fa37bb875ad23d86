#pragma once
/// Body models of the built-in phantoms at named sizes: the tet volume (tetrahedralize()), a separate,
/// isotropically remeshed skin and the tracking connections between them. The `paper` sizes reproduce Table 1
/// of Frerichs, Vidler and Gatzidis 2020 (arm: 29k volume nodes, 141k tets, 19k skin triangles; head: 35k
/// nodes, 149k tets, 122k skin triangles); `small` is for quick tests and previews, `fine` for close-ups.

#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/tracking.hpp"
#include "tetrahedralize/tetrahedralize.hpp"

namespace forensim {

/// Sizes of a phantom body model.
struct PhantomModelSize {
  std::string phantom, name;     ///< "arm" / "head"; "small" / "paper" / "fine"
  std::size_t volume_nodes = 0;  ///< target node count of the tet volume (within count_tolerance)
  double initial_edge_mm = 0.0;  ///< calibrated first guess for the node target (one meshing pass)
  /// Bound on the tets' radius-edge ratio: 3 (faster grading from the fine surfaces to the interior, fewer
  /// tets per node) where the paper's tets-per-node ratio needs it.
  double radius_edge_bound = 2.0;
  std::size_t skin_triangles = 0;  ///< target triangle count of the skin (within 10 %)
  double surface_voxel_mm = 2.0;   ///< voxel of the skin and bone surfaces given to the tetrahedraliser
  double skin_voxel_mm = 1.0;      ///< voxel of the iso-surface the skin is remeshed from
  /// The paper's Table 1 figures for this phantom (0 when the paper has none): nodes, tets, skin triangles.
  std::size_t paper_nodes = 0, paper_tets = 0, paper_skin_triangles = 0;
  /// Largest sliver bound (smallest dihedral angle, degrees) asked of Mesh_3's perturbation and exudation for
  /// this phantom: the head's thin skull keeps one tet near 7.5 degrees that perturbation cannot lift, and
  /// asking 8 or more makes it run for minutes without gain (7 takes seconds).
  double sliver_bound_deg = 12.0;
};

/// Names of the sizes: small, paper, fine.
std::vector<std::string> phantom_model_size_names();

/// The sizes of `phantom` ("arm" or "head") at `size` ("small", "paper" or "fine"). Throws InputError for an
/// unknown phantom or size, listing the known ones.
PhantomModelSize phantom_model_size(const std::string& phantom, const std::string& size);

/// What make_phantom_model() did, for reports.
struct PhantomModelReport {
  TetrahedralizeReport volume;
  std::size_t skin_triangles = 0, skin_vertices = 0;
  double skin_mean_edge_mm = 0.0;
  TrackingStats tracking;
  double seconds_surfaces = 0.0, seconds_volume = 0.0, seconds_skin = 0.0, seconds_tracking = 0.0;
  std::string summary() const;
};

/// Builds the body model of a phantom: skin and bone iso-surfaces tetrahedralised to `size.volume_nodes`
/// nodes (flesh and bone labels), a skin remeshed isotropically to about `size.skin_triangles` triangles,
/// the tracking connections of every skin vertex, and the phantom's parts per skin vertex and tet.
/// Deterministic. `mesh_options` sets quality and seed (its size fields and radius-edge bound are overridden).
BodyModel make_phantom_model(const PhantomModelSize& size, const TetrahedralizeOptions& mesh_options = {},
                             PhantomModelReport* report = nullptr);

}  // namespace forensim
