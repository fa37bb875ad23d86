#pragma once
/// Where a scan has data. A CT's iso-surface is closed where the anatomy leaves the scanned volume (headsq: the
/// vault cut off above the orbits, the neck at the last slice): there the surface is a flat cap just outside the
/// sample lattice, where the volume was padded with background (volume/iso_surface.hpp). Such a cap is no anatomy,
/// and nothing beyond the lattice was seen. Registration (skull_registration.hpp) and the face evaluation
/// (face_evaluation.hpp) ask this object whether a point lies in the scanned region and which surface triangles
/// are caps, so that the missing parts of a partial scan are neither matched nor measured.
///
/// A mesh skull (a surface scan) has no lattice: the default object is unbounded and finds no caps.

#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

class ScanFieldOfView {
 public:
  /// Unbounded: every point is in view, no triangle is a cap.
  ScanFieldOfView() = default;
  /// The sample lattice of `grid` (its oriented box from sample 0 to sample n-1 on each axis). Throws InputError
  /// for an invalid grid.
  static ScanFieldOfView of_volume(const ScalarGrid& grid);

  /// False for the default (unbounded) object.
  bool bounded() const { return m_bounded; }
  /// The largest sample spacing of the lattice (mm); 0 when unbounded.
  double max_spacing_mm() const { return m_bounded ? m_spacing.maxCoeff() : 0.0; }
  /// True when `point` (world mm) lies inside the lattice box, at least `margin_mm` from each of its faces (a
  /// negative margin lets the point lie that far outside). Always true when unbounded.
  bool contains(const Vec3& point, double margin_mm = 0.0) const;
  /// Distance (mm) from `point` inside the box to the nearest box face; negative outside (the largest overshoot);
  /// +infinity when unbounded.
  double depth_mm(const Vec3& point) const;
  /// Per triangle of `surface`: 1 when it is a cap, i.e. every vertex lies within a quarter sample of the same
  /// face of the lattice box or beyond it and the triangle's normal points out of that face (cos > 0.7); else 0.
  /// All 0 when unbounded.
  std::vector<char> cap_triangles(const TriMesh& surface) const;

 private:
  bool m_bounded = false;
  Vec3 m_origin = Vec3::Zero();
  Mat3 m_world_to_index = Mat3::Identity();
  Mat3 m_direction = Mat3::Identity();  ///< columns: unit world directions of the lattice axes
  Vec3 m_spacing = Vec3::Ones();        ///< mm per index step along each axis
  Vec3 m_last = Vec3::Zero();           ///< index of the last sample along each axis (n - 1)
};

}  // namespace forensim
