#pragma once
/// Landmark directions and tissue-depth vectors on a skull (Kahler, Haber and Seidel 2003, section 3 and
/// eq. before (1)): "each landmark is associated with a vector in surface normal direction, corresponding to
/// the typical direction of thickness measurements"; the vector is scaled to the landmark's tissue depth, and
/// the skin landmark is q_i = s_i + d_i. The normal is averaged over a small patch of the skull around the
/// landmark so that the triangulation's noise (CT staircase, scan facets) does not tilt it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "geometry/tri_mesh.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {

/// A skull prepared for landmark queries: closest points (Embree BVH), face normals and areas, and edge
/// adjacency for growing patches. Setup once, query many; queries are const and thread-safe.
class SkullSurface {
 public:
  /// `skull`: closed or open triangle mesh in mm, counter-clockwise seen from outside (outward normals).
  /// Throws InputError naming "skull mesh" when it is invalid or has no triangles.
  explicit SkullSurface(const TriMesh& skull);
  ~SkullSurface();
  SkullSurface(SkullSurface&&) noexcept;
  SkullSurface& operator=(SkullSurface&&) noexcept;

  /// Closest point of the skull to `point` (mm).
  ClosestPoint closest_point(const Vec3& point) const;

  /// Unit normal averaged over the patch around `at`: the triangles edge-connected to at.triangle whose
  /// closest point to at.point lies within `radius_mm` and whose normal faces the same half-space as
  /// at.triangle's (so the far side of thin bone is not mixed in), each weighted by the area of its part
  /// inside the ball (estimated on a 4 x 4 barycentric subdivision of the triangle). A radius smaller than the
  /// triangles falls back to at.triangle's normal. Points out of the skull (outward normals).
  Vec3 patch_normal(const ClosestPoint& at, double radius_mm) const;

  /// Direction of a landmark: patch_normal() at the landmark's closest skull point.
  Vec3 landmark_direction(const Vec3& landmark_mm, double radius_mm) const;

  const TriMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

struct DepthVectorOptions {
  double patch_radius_mm = 5.0;         ///< radius of the patch the normal is averaged over
  double max_surface_offset_mm = 10.0;  ///< a landmark farther from the skull than this is an error
};

/// One tissue-depth vector.
struct DepthVector {
  std::string bone_landmark;       ///< canonical name on the skull ("n", "zy_L")
  std::string skin_landmark;       ///< its pair on the skin ("se'", "zy'_L")
  Vec3 bone_mm = Vec3::Zero();     ///< s_i: the landmark moved onto the skull surface (its closest point)
  Vec3 direction = Vec3::Zero();   ///< unit skull normal averaged over the patch
  double depth_mm = 0.0;           ///< tissue depth from the table
  Vec3 skin_mm = Vec3::Zero();     ///< q_i = s_i + depth * direction
  double surface_offset_mm = 0.0;  ///< distance of the landmark as given from the skull surface
  LandmarkSource source = LandmarkSource::imported;  ///< the bone landmark's source
  double confidence = 1.0;                           ///< the bone landmark's confidence
  std::string depth_source;                          ///< publication (and variant) the depth comes from
};

/// Depth vectors of a set of skull landmarks.
struct DepthVectors {
  std::vector<DepthVector> vectors;   ///< one per bone landmark with a skin pair and a depth, in set order
  std::vector<std::string> missing;   ///< bone landmarks with a skin pair but no depth in the table
  std::vector<std::string> unpaired;  ///< landmarks that have no skin pair (porion, orbitale, ...) or are not bone
};

/// The depth vectors of `skull_landmarks` (names resolved through the built-in vocabulary; unknown names are an
/// InputError with "did you mean") with depths from `depths`. Throws InputError naming the landmark when it lies
/// farther than options.max_surface_offset_mm from the skull.
DepthVectors depth_vectors(const SkullSurface& skull, const LandmarkSet& skull_landmarks, const TissueDepths& depths,
                           const DepthVectorOptions& options = {});

/// The skin landmarks q_i of depth vectors, named by their skin landmark, with the bone landmark's source and
/// confidence: the targets of the template warp.
LandmarkSet skin_landmarks(const DepthVectors& vectors, const std::string& name = "skin");

}  // namespace forensim
