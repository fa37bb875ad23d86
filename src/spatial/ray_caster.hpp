#pragma once
/// Ray casting against a triangle mesh on Embree 3: which triangle a ray hits first, where, and with which
/// barycentric coordinates. Used to attach the desiccation skin to the tet volume (rays along negative
/// vertex normals), and by the wound system to pick the triangle under a screen point.

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Which side of a triangle a ray may hit. The front side is the one its outward (counter-clockwise)
/// normal points to: a ray hits the front when direction.dot(normal) < 0.
enum class FaceCulling {
  none,   ///< hits on both sides count
  back,   ///< hits on back faces are ignored (the ray passes through them)
  front,  ///< hits on front faces are ignored
};

/// First hit of a ray.
struct RayHit {
  Index triangle = -1;              ///< index into mesh.triangles
  Vec3 barycentric = Vec3::Zero();  ///< weights of the triangle's vertices 0, 1, 2 (each >= 0, sum 1)
  double t = 0.0;                   ///< ray parameter: point ~ origin + t * direction (distance if direction is unit)
  Vec3 point = Vec3::Zero();        ///< hit point on the triangle, = sum of barycentric weights times vertices
  Vec3 normal = Vec3::Zero();       ///< unit geometric normal of the hit triangle (counter-clockwise = outward)
};

/// Exact ray/triangle intersection in double (Moeller and Trumbore 1997). Returns true when the line
/// origin + t * direction meets triangle (a, b, c) inside or on its edges with t in [t_min, t_max];
/// then sets `t` and `barycentric` (weights of a, b, c). Degenerate triangles and rays parallel to the
/// triangle's plane never hit. The reference for RayCaster's tests.
bool ray_triangle_intersect(const Vec3& origin, const Vec3& direction, const Vec3& a, const Vec3& b, const Vec3& c,
                            double t_min, double t_max, double& t, Vec3& barycentric);

/// First hit of one ray by testing every triangle in double, O(#F): for one-off queries (build a RayCaster
/// for more) and as a reference. Same conventions as RayCaster::intersect(); ties in t go to the lower
/// triangle index. The mesh is not validated (indices must be in range).
std::optional<RayHit> intersect_ray(const TriMesh& mesh, const Vec3& origin, const Vec3& direction, double t_min = 0.0,
                                    double t_max = std::numeric_limits<double>::infinity(),
                                    FaceCulling culling = FaceCulling::none);

/// Setup-once, query-many ray caster. The constructor copies the mesh (positions and triangles only) and
/// builds Embree's BVH; queries are const and thread-safe. Embree intersects in float (vertices relative to
/// the mesh's bounding-box centre); each hit is then refined in double against the triangle Embree found,
/// so `t` (kept within [t_min, t_max]), `point` and `barycentric` agree with ray_triangle_intersect() to double
/// rounding (except that
/// barycentrics slightly outside [0, 1], for hits on an edge, are clamped onto the triangle).
class RayCaster {
 public:
  /// Validates `mesh` (throws InputError naming "ray caster mesh") and builds the BVH. An empty mesh is
  /// allowed and is never hit.
  explicit RayCaster(const TriMesh& mesh);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;

  /// First hit along origin + t * direction with t in [t_min, t_max], or nullopt. `direction` need not be
  /// unit but must be finite and non-zero (else InputError); 0 <= t_min <= t_max.
  std::optional<RayHit> intersect(const Vec3& origin, const Vec3& direction, double t_min = 0.0,
                                  double t_max = std::numeric_limits<double>::infinity(),
                                  FaceCulling culling = FaceCulling::none) const;

  /// intersect() for rays i = 0..#origins-1 (origins[i], directions[i]), in parallel; result i belongs to
  /// ray i whatever the thread count. `directions` must have as many entries as `origins`.
  std::vector<std::optional<RayHit>> intersect_batch(const std::vector<Vec3>& origins,
                                                     const std::vector<Vec3>& directions, double t_min = 0.0,
                                                     double t_max = std::numeric_limits<double>::infinity(),
                                                     FaceCulling culling = FaceCulling::none) const;

  /// True when the ray hits anything with t in [t_min, t_max] (shadow/visibility test; cheaper than
  /// intersect()). Same argument rules as intersect().
  bool occluded(const Vec3& origin, const Vec3& direction, double t_min = 0.0,
                double t_max = std::numeric_limits<double>::infinity(), FaceCulling culling = FaceCulling::none) const;

  std::size_t triangle_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace forensim
