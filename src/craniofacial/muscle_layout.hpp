#pragma once
/// Facial muscles as layout grids on the skin (Kähler, Haber and Seidel 2003, section 4.1, after Kähler et al.
/// 2002): each muscle is a grid of points laid out on the skin surface; the muscle's shape (its fibres) is
/// computed from the grid to lie under the skin. Fitting a template to a skull warps the grid points with the
/// same RBF as the skin (eq. 1) and then recomputes the shape under the warped skin, so the muscles follow the
/// new face. Fibres are the grid's rows: a linear muscle contracts along them toward its origin (row 0), a
/// sphincter's rows are closed rings contracting toward its centre.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

enum class MuscleKind {
  linear,    ///< fibres from a bony origin (grid row 0 end) to a skin insertion
  sphincter  ///< concentric closed rings around an opening (orbicularis oris, orbicularis oculi)
};

/// One muscle's layout grid: `fibre_count` fibres of `samples_per_fibre` points each, row-major
/// (point [f * samples_per_fibre + s] is sample s of fibre f). Linear: each fibre runs from origin (s = 0) to
/// insertion; sphincter: each fibre is a closed ring (the last sample connects back to the first), fibre 0
/// innermost.
struct MuscleLayout {
  std::string name;  ///< e.g. "zygomaticus_major_L" (L/R: the patient's side)
  MuscleKind kind = MuscleKind::linear;
  int fibre_count = 0;
  int samples_per_fibre = 0;
  std::vector<Vec3> grid;     ///< fibre_count * samples_per_fibre points on the skin (mm)
  double thickness_mm = 3.0;  ///< depth of the fibres' centre under the skin
};

/// A muscle shaped under a skin: the grid points on the skin and the fibre points `thickness_mm` under it.
struct MuscleShape {
  std::string name;
  MuscleKind kind = MuscleKind::linear;
  int fibre_count = 0;
  int samples_per_fibre = 0;
  std::vector<Vec3> skin_points;         ///< grid points moved onto the skin (closest points), mm
  std::vector<Index> skin_triangles;     ///< skin triangle of each skin point (its attachment)
  std::vector<Vec3> skin_barycentrics;   ///< barycentric weights in that triangle
  std::vector<Vec3> fibre_points;        ///< under the skin: skin point - thickness * interpolated skin normal
  std::vector<double> fibre_lengths_mm;  ///< rest length of each fibre (closed rings include the closing segment)
};

/// Shapes each layout under `skin` (validated; vertex normals used when present, else computed): every grid
/// point goes to its closest point on the skin, and its fibre point `thickness_mm` inward along the
/// interpolated vertex normal there. Parallel, deterministic. Throws InputError for an empty skin, a layout
/// whose grid size is not fibre_count * samples_per_fibre (naming the muscle) or non-finite grid points.
std::vector<MuscleShape> shape_muscles(const std::vector<MuscleLayout>& layouts, const TriMesh& skin);

/// The paper's 24 facial muscles laid out on the `head` phantom's face (head frame: LPS mm, x the patient's
/// left, y posterior, z superior; the face looks toward -y): 21 linear (frontalis, corrugator supercilii,
/// levator labii superioris alaeque nasi, levator labii superioris, zygomaticus minor, zygomaticus major,
/// levator anguli oris, risorius, depressor anguli oris, depressor labii inferioris, each _L and _R, and the
/// midline procerus) and 3 sphincters (orbicularis oris, orbicularis oculi _L and _R). Each is built from anchor
/// points (origin, insertion and width; or centre and radii) chosen on the phantom; the grids are near the skin
/// but not on it: shape_muscles() puts them there. `fibre_count` >= 2 and `samples_per_fibre` >= 3, else
/// InputError.
std::vector<MuscleLayout> head_phantom_muscle_layouts(int fibre_count = 5, int samples_per_fibre = 9);

/// Names of the 24 muscles in the order head_phantom_muscle_layouts() returns them.
std::vector<std::string> facial_muscle_names();

}  // namespace forensim
