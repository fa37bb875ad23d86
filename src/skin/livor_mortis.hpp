#pragma once
/// The livor mortis start state of the mummification skin shading (Frerichs et al. 2020, section 9.4: the
/// livor mortis method of Frerichs et al. 2016 is applied before the drying starts). After death the blood
/// sinks under gravity and fills the vessels of the lowest parts of the body (hypostasis: bluish purple there,
/// pale on top); where the body rests on a surface the pressure closes the vessels, so those areas stay pale.
///
/// forensim computes the settled (fixed) state directly rather than by flowing blood along tet edges: with
/// capacity limits, the flow of the 2016 method ends with the lowest vessels full. Per skin vertex i at height
/// z_i (along -gravity, mm) with area a_i (one third of its triangles), capacity M_i (1 by default, the
/// fraction `contact_capacity` of it in contact areas) and fill
///     h_i = r + (1 - r) S((z* - z_i) / w),  S(x) = smoothstep from x = -1 to 1,
/// the blood level z* is found by bisection so that the blood is conserved:
///     sum_i a_i M_i h_i = h_0 sum_i a_i M0_i
/// (h_0: the uniform fill before settling, M0: the capacity before the body rested on the surface), so blood
/// pressed out of the contact areas settles elsewhere. r is the residual fill of drained vessels and w the
/// half width of the transition band, a capillary fringe of about a tenth of the body's height range.

#include <cstdint>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct LivorSettings {
  Vec3 gravity = Vec3(0, 0, -1);      ///< direction of gravity in the mesh frame (normalised here)
  double blood_fill = 0.35;           ///< h_0: mean fill of the skin's vessel capacity before settling, (r, 1]
  double residual_fill = 0.04;        ///< r: fill of drained vessels at the top, [0, blood_fill)
  double transition_fraction = 0.05;  ///< w as a fraction of the height range (used when transition_mm <= 0)
  double transition_mm = 0.0;         ///< w in mm, if > 0
  double contact_capacity = 0.05;     ///< capacity left in contact areas (pressure pallor), [0, 1]
  double oxygen = 0.15;               ///< o: oxygen saturation of the settled, deoxygenated blood, [0, 1]
};

/// Per-vertex livor mortis state: the inputs of the skin shader. Arrays have #V entries.
struct LivorState {
  std::vector<double> vertex_hemoglobin;            ///< h: fill of the vessel capacity, [0, 1] (eq. 37)
  std::vector<double> vertex_capacity;              ///< M: available capacity ratio, [0, 1] (eq. 37)
  std::vector<double> vertex_saturation;            ///< s = h M, the hemoglobin saturation before drying (eq. 37)
  std::vector<double> vertex_oxygen;                ///< o: oxygen saturation of the blood, [0, 1] (eq. 38)
  std::vector<std::uint8_t> vertex_contact;         ///< 1 where the body rests on the surface
  double blood_level_mm = 0.0;                      ///< z*, height of the blood level along -gravity
  double height_min_mm = 0.0, height_max_mm = 0.0;  ///< height range of the skin along -gravity
  double transition_mm = 0.0;                       ///< w used
  double blood_volume = 0.0;  ///< sum a_i M_i h_i (mm^2 times capacity), conserved by the settling
};

/// Vertices within `distance_mm` of the supporting plane: the plane perpendicular to `gravity` through the
/// lowest vertex, raised by `plane_offset_mm`. #V flags. Throws InputError for a zero gravity or a negative
/// distance.
std::vector<std::uint8_t> contact_near_plane(const TriMesh& skin, const Vec3& gravity, double distance_mm,
                                             double plane_offset_mm = 0.0);

/// Per-vertex mask from a per-face mask (#F flags): a vertex is in contact when any of its faces is.
std::vector<std::uint8_t> vertex_mask_from_faces(const TriMesh& skin, const std::vector<std::uint8_t>& face_mask);

/// Settles the blood of `skin` (mm) under `settings.gravity`. `contact`: #V flags or empty (no contact);
/// `capacity`: #V capacity ratios M0 in [0, 1] before contact, or empty for 1. Deterministic. Throws
/// InputError for wrong array sizes, values out of range or an empty mesh.
LivorState settle_livor(const TriMesh& skin, const std::vector<std::uint8_t>& contact,
                        const LivorSettings& settings = {}, const std::vector<double>& capacity = {});

}  // namespace forensim
