#pragma once
/// Where a fitted skin and its skull intersect (Kähler, Haber and Seidel 2003, section 4.2, Figure 6a: with
/// only the user's landmarks "some skull areas still intersect the skin"): skull vertices outside the skin and
/// skin vertices inside the skull, by the generalised winding number (spatial/winding_number.hpp), which also
/// classifies points of skulls with small holes. Reported before and after interpolated landmarks.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

class ClosestPointQuery;
class WindingNumber;

struct SkullSkinViolations {
  std::size_t skull_vertex_count = 0;
  std::size_t skin_vertex_count = 0;
  std::size_t skull_outside_skin = 0;    ///< skull vertices where the skin's winding number is below 1/2
  std::size_t skin_inside_skull = 0;     ///< skin vertices where the skull's winding number is above 1/2
  double max_skull_protrusion_mm = 0.0;  ///< largest distance of an outside skull vertex from the skin
  double max_skin_intrusion_mm = 0.0;    ///< largest distance of an inside skin vertex from the skull surface
  std::vector<std::size_t> skull_vertices_outside;  ///< their indices, ascending
  std::vector<std::size_t> skin_vertices_inside;    ///< their indices, ascending
  std::size_t total() const { return skull_outside_skin + skin_inside_skull; }
};

/// Counts the violations between `skull` and `skin` (both validated; the skin should be closed, the skull
/// closed or nearly: InputError for empty or invalid meshes): a winding-number evaluation at every vertex of
/// both. Parallel, deterministic. The one-call form; SkullSkinViolationCounter gives the same counts faster for
/// one skull and a sequence of skins.
SkullSkinViolations count_skull_skin_violations(const TriMesh& skull, const TriMesh& skin);

/// Violation counts of one skull against a sequence of skins with the same triangles (the template's skin after
/// successive warps: the fit's correction rounds, the guides' second warp). The skull's winding-number tree, its
/// closest-point query and a grid of its vertices are built once (on the first count). Each count remembers the
/// skin and the sides it found; a next skin with the same triangles re-evaluates only the points whose side
/// can have changed, with the same winding-number evaluation as count_skull_skin_violations:
/// - a skull vertex v keeps its side unless it lies within delta_T of some skin triangle T as it was, delta_T the
///   largest displacement of T's corners: the triangle moved linearly sweeps only points that close to it, so a
///   closed skin (every edge in two triangles) cannot have crossed v, and its winding number there, an integer
///   away from the surface, is unchanged;
/// - a skin vertex that moved by delta keeps its side unless the skull comes within delta of where it was (the
///   segment it moved along crosses no skull triangle), used only for a closed skull: the generalised winding
///   number of an open one varies continuously around its holes.
/// The last 3 skins are remembered, and each count starts from the one whose vertices moved least. A skin with
/// other triangles, or moved so far that the search would cost more than evaluating every skull vertex, is
/// counted anew; for a closed skin the skull vertices are then grouped first: a vertex with no skin point within
/// its longest edge shares its side with its neighbours (no edge from it can cross the skin), and the winding
/// number is evaluated once per group of vertices joined so. Open skins are evaluated at every vertex. The counts,
/// index lists and distances equal count_skull_skin_violations(skull, skin) (the winding number's far-field error,
/// below 1e-2, never moves a point off the surface across 1/2). Not thread-safe (counting updates the remembered skin).
class SkullSkinViolationCounter {
 public:
  /// Copies `skull` (validated, with triangles: InputError as count_skull_skin_violations).
  explicit SkullSkinViolationCounter(const TriMesh& skull);
  ~SkullSkinViolationCounter();
  SkullSkinViolationCounter(const SkullSkinViolationCounter&) = delete;
  SkullSkinViolationCounter& operator=(const SkullSkinViolationCounter&) = delete;

  /// Builds the skull's trees now (else the first count does).
  void prepare() const { build(); }
  /// The violations between the skull and `skin` (validated, with triangles).
  SkullSkinViolations count(const TriMesh& skin);

  const TriMesh& skull() const { return m_skull; }
  /// Closest points on the skull (built on first use; shared with violation_correction_pairs).
  const ClosestPointQuery& skull_closest() const;
  /// Winding-number evaluations of the last count (at most #skull + #skin vertices).
  std::size_t last_evaluated() const { return m_last_evaluated; }

 private:
  void build() const;
  /// Skull vertices within the swept reach of the remembered skin's triangles moving to `positions`; false when
  /// the search would cost more than a full evaluation.
  bool swept_skull_vertices(const std::vector<Vec3>& old, const std::vector<Vec3>& positions,
                            std::vector<std::uint32_t>& out) const;
  /// Sides of all skull vertices against the closed `skin` (`winding` its tree, `closest` its closest points), by
  /// the groups above; returns the number of winding-number evaluations.
  std::size_t grouped_sides(const WindingNumber& winding, const ClosestPointQuery& closest,
                            std::vector<char>& outside) const;

  TriMesh m_skull;
  mutable std::unique_ptr<WindingNumber> m_skull_winding;
  mutable std::unique_ptr<ClosestPointQuery> m_skull_closest;
  mutable bool m_skull_closed = false;
  /// Uniform grid over the skull's vertices: cell (i, j, k) holds grid_vertices[grid_start[c] .. grid_start[c+1]).
  mutable Vec3 m_grid_origin = Vec3::Zero();
  mutable double m_grid_cell_mm = 1.0;
  mutable int m_grid_size[3] = {1, 1, 1};
  mutable std::vector<std::uint32_t> m_grid_start, m_grid_vertices;
  /// The skull's edges (each once, lower index first) and each vertex's longest edge (mm).
  mutable std::vector<std::array<std::uint32_t, 2>> m_skull_edges;
  mutable std::vector<double> m_skull_reach;

  /// A counted skin and the sides found: the next count starts from the nearest of the last few.
  struct Counted {
    std::vector<Vec3> skin_positions;
    std::vector<char> skull_outside;  ///< per skull vertex
    std::vector<char> skin_inside;    ///< per skin vertex
  };
  std::vector<Counted> m_counted;  ///< most recent first, all with the triangles below
  std::vector<Tri> m_skin_triangles;
  bool m_skin_closed = false;
  std::size_t m_last_evaluated = 0;
};

}  // namespace forensim
