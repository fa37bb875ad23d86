#pragma once
/// Shape quality of tetrahedral meshes: radius-edge ratios and dihedral angles, the measures Mesh_3 and
/// TetGen bound, reported per tet and as statistics with fixed-bin histograms.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim {

/// Circumradius of tet (a, b, c, d) divided by its shortest edge (Shewchuk's radius-edge ratio): sqrt(6)/4 ~
/// 0.612 for the regular tet, unbounded for slivers' neighbours (needles, caps); +infinity for a flat tet.
double tet_radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Smallest of the six interior dihedral angles of tet (a, b, c, d), in degrees: 70.53 for the regular
/// tet, 0 for a flat one. Independent of orientation.
double tet_min_dihedral_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Quality statistics of a tet mesh (tet_quality()).
struct TetQualityReport {
  std::size_t tet_count = 0;
  std::size_t inverted_count = 0;         ///< signed volume < 0
  std::size_t flat_count = 0;             ///< |volume| <= 1e-12 times the cube of the longest edge
  std::vector<double> radius_edge_ratio;  ///< per tet (infinity for flat tets)
  std::vector<double> min_dihedral_deg;   ///< per tet
  double radius_edge_min = 0.0, radius_edge_mean = 0.0, radius_edge_max = 0.0;  ///< over non-flat tets
  double dihedral_min = 0.0, dihedral_mean = 0.0, dihedral_max = 0.0;           ///< degrees, over all tets
  /// Upper edges of the radius-edge histogram bins; bin i counts ratios in (edge[i-1], edge[i]], the last
  /// bin everything above the last edge (and flat tets).
  static constexpr std::array<double, 7> radius_edge_bin_edges{0.7, 0.8, 1.0, 1.25, 1.5, 2.0, 3.0};
  std::array<std::size_t, 8> radius_edge_histogram{};
  /// Minimum dihedral angle histogram: 5-degree bins [0,5), [5,10), ..., [70,75] (15 bins).
  static constexpr double dihedral_bin_deg = 5.0;
  std::array<std::size_t, 15> dihedral_histogram{};

  /// Several lines: counts, min/mean/max of both measures and both histograms as text bars.
  std::string summary() const;
};

/// Radius-edge ratio and minimum dihedral angle of every tet of `mesh` with statistics and histograms.
/// Throws InputError (via mesh.validate) for out-of-range indices or non-finite positions.
TetQualityReport tet_quality(const TetMesh& mesh);

}  // namespace forensim
