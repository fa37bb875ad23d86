#pragma once
/// Tetrahedral body models: a closed skin surface and the bone surfaces inside it (or a CT volume) to a
/// labelled, surface-conforming tet mesh whose tets are flesh (tissue_flesh) or bone (tissue_bone), as the
/// desiccation system's object representation needs (paper section 4, Table 1). Built on CGAL Mesh_3 with
/// a polyhedral complex domain (skin: flesh | outside, each bone: bone | flesh), which samples the boundary
/// and interfaces on the input triangles themselves.

#include <string>
#include <vector>

#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

struct TetrahedralizeOptions {
  /// Target edge length (mm) of the tets. 0 = derive it from target_nodes (or target_tets).
  double edge_length_mm = 0.0;
  /// Target number of tet-mesh nodes, used when edge_length_mm is 0: an edge length is estimated from the
  /// enclosed volume, the mesh is built, and rebuilt once with a corrected length if the count is off by
  /// more than `count_tolerance`.
  std::size_t target_nodes = 0;
  /// Target number of tets, used when edge_length_mm and target_nodes are 0.
  std::size_t target_tets = 0;
  double count_tolerance = 0.05;
  /// First edge length (mm) tried for a count target, e.g. one calibrated for a phantom preset; 0 = estimate
  /// it from the enclosed volume. A good hint makes one pass enough.
  double initial_edge_mm = 0.0;
  /// Interior tets may be this many times larger than the edge length (the boundary keeps the edge length):
  /// > 1 puts more of the nodes on the surfaces, as simulation meshes that resolve the skin need.
  double interior_size_factor = 1.0;
  /// Upper bound of the tets' circumradius / shortest edge (Mesh_3 cell_radius_edge_ratio; >= 2 for
  /// guaranteed termination).
  double radius_edge_bound = 2.0;
  /// Sliver exudation target: smallest dihedral angle (degrees) the optimiser tries to reach.
  double min_dihedral_deg = 12.0;
  /// Largest distance (mm) between the boundary triangles and the input surfaces, as a fraction of the edge
  /// length; the volume error shrinks with it.
  double surface_distance_fraction = 0.01;
  /// Floor (mm) of that distance, e.g. a fraction of a CT's voxel so the mesh does not chase voxel steps.
  double min_surface_distance_mm = 0.0;
  /// Boundary triangles' smallest angle (degrees, <= 30).
  double facet_angle_deg = 25.0;
  /// Ask Mesh_3 for a 2-manifold boundary (refines until every boundary vertex has a disk neighbourhood).
  bool manifold_boundary = true;
  /// Mesh_3's sliver perturbation (slower, raises the smallest dihedral angles); exudation always runs, bounded
  /// at ten times the refinement's time (at least a minute; a note says when it was cut short).
  bool perturb = true;
  /// Also close openings larger than a quarter of a surface's size (a bust's base, a limb cut off at the
  /// wrist) with a refined, faired cap; by default only scan-sized holes are filled and a surface with a large
  /// opening is rejected.
  bool close_openings = false;
  /// > 0 and no bone surfaces given: the bone is the skin's inner offset surface this deep (mm;
  /// volume/offset_surface.hpp), a stand-in skeleton for scans, which have no bones (0: none).
  double bone_offset_mm = 0.0;
  /// Meshing stops with an InputError when a pass reaches this many nodes (a guard against runaway refinement,
  /// which would fill the memory: about 2 GB per million nodes). Each pass is also bounded at 50 times the
  /// nodes its edge length should give (at least 100,000), whichever is lower.
  std::size_t max_nodes = 3000000;
  /// Each meshing pass's refinement stops with an InputError after this many seconds (0: automatic, 300 s
  /// plus 1 s per 2,000 expected nodes, more than ten times a normal run's). Refinement that never converges
  /// (the manifold criterion at surfaces that touch themselves or each other along an edge or at a point) ends
  /// here instead of running forever. An interruption (interrupt_requested()) stops it with CancelledError.
  double time_limit_s = 0.0;
  /// Seed of Mesh_3's random choices (results are deterministic for a given seed and thread count).
  unsigned seed = 0;
};

/// What tetrahedralize() did.
struct TetrahedralizeReport {
  double edge_length_mm = 0.0;       ///< edge length of the final mesh's criteria
  int passes = 0;                    ///< meshing passes (2 when a node/tet count target needed a correction)
  double skin_volume_mm3 = 0.0;      ///< enclosed by the input skin
  double bone_volume_mm3 = 0.0;      ///< enclosed by the input bones
  double tet_volume_mm3 = 0.0;       ///< all tets
  double bone_tet_volume_mm3 = 0.0;  ///< bone-labelled tets
  std::size_t node_count = 0, tet_count = 0, bone_tet_count = 0;
  double seconds_prepare = 0.0, seconds_mesh = 0.0;
  std::vector<std::string> notes;  ///< repairs and clipping done on the inputs, in words
  std::string summary() const;
};

/// The closed, outward copy of a body surface that tetrahedralize() meshes (positions and triangles only): checked,
/// repaired with repair_mesh() when open, non-manifold or degenerate (scan-sized holes filled; with
/// `close_openings` every opening, capped and faired), freed of self-intersections (remove_self_intersections():
/// the mesher needs an embedded surface; InputError when that fails) and flipped when it faces inward. What was done is
/// appended to `notes`. Throws InputError naming `name` for an empty surface or one that stays open.
TriMesh closed_body_surface(const TriMesh& input, const std::string& name, bool close_openings,
                            std::vector<std::string>& notes);

/// Tetrahedralises the volume inside `skin` (closed, outward triangles in mm), labelling tets inside any of
/// `bones` tissue_bone and the rest tissue_flesh. The boundary and the flesh/bone interfaces are sampled on
/// the input surfaces (within options.surface_distance_fraction of the edge length); every tet is positively
/// oriented; quality follows options. Open or non-manifold inputs are first repaired with repair_mesh();
/// an empty surface, one that stays open, a bone reaching outside the skin or two overlapping bones throw InputError
/// naming "skin surface" or "bone surface <i>", and so does a bone whose triangles cross the skin's or another
/// bone's (Mesh_3's polyhedral complex domain needs patches that do not cross). A pass whose refinement has not
/// converged within its node or time bound (max_nodes, time_limit_s) throws InputError; an interruption,
/// CancelledError. Node and tet order are deterministic for a given seed.
TetMesh tetrahedralize(const TriMesh& skin, const std::vector<TriMesh>& bones, const TetrahedralizeOptions& options,
                       TetrahedralizeReport* report = nullptr);

/// Skin and bone surfaces of a CT volume, as tetrahedralize_ct meshes them: the skin is the largest component
/// of the `skin_iso` iso-surface, the bones the components of the `bone_iso` iso-surface that lie inside the
/// skin and enclose at least 0.5 % of the largest one's volume, their vertices kept half the smallest voxel spacing
/// below the skin (the separately smoothed iso-surfaces cross where the soft tissue is thinner than a voxel)
/// (extract_iso_surface with 10 Taubin steps to remove voxel staircases; values above the iso-value are inside). Throws
/// InputError for non-finite iso-values, bone not above skin, or no skin.
struct CtBodySurfaces {
  TriMesh skin;
  std::vector<TriMesh> bones;  ///< one surface (all kept components) or none
};
CtBodySurfaces ct_body_surfaces(const ScalarGrid& grid, double skin_iso, double bone_iso);

/// Tetrahedralises a CT volume: ct_body_surfaces() meshed by tetrahedralize(), with the boundary asked to
/// follow the surfaces no closer than half the smallest voxel spacing (the surfaces are no more accurate than
/// that) and without the manifold criterion (thin skulls nearly touch themselves; the boundary stays closed
/// but may have non-manifold vertices where they do).
TetMesh tetrahedralize_ct(const ScalarGrid& grid, double skin_iso, double bone_iso,
                          const TetrahedralizeOptions& options, TetrahedralizeReport* report = nullptr);

}  // namespace forensim
