#pragma once
/// Strokes drawn on the screen over a view of the skin mesh (Linnenbank 2015, chapter 4.2.1, "UV
/// recording"): a ray is cast from the camera through each screen point; where it hits the mesh, the hit
/// point's barycentric coordinates in the hit triangle (eq. 4.2) give its position (eq. 4.1) and its UV
/// (eq. 4.3). Points whose ray misses the mesh are not recorded, as in the thesis (the user is drawing off
/// the mesh). The recorded surface points make a WoundStroke, painted like any other (wound_canvas.hpp).

#include <cstddef>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "render/camera.hpp"
#include "spatial/ray_caster.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim {

/// Eq. 4.2: barycentric coordinates (s, r, t) of point P of triangle (A, B, C), the weights of A, B and C,
/// from the areas of the sub-triangles: with u = B - A, v = C - A, w = P - A,
///   r = |v x w| / |u x v|,  t = |u x w| / |u x v|,  s = 1 - r - t.
/// Exact for P inside the triangle (on its plane); outside it the magnitudes lose the sign. Returns
/// (1, 0, 0) for a degenerate triangle (|u x v| = 0).
Vec3 barycentric_from_areas(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p);

/// Eqs. 4.1 and 4.3: the interpolation of three corner values (positions or UVs) with weights (s, r, t).
template <typename T>
T barycentric_blend(const Vec3& weights, const T& a, const T& b, const T& c) {
  return weights.x() * a + weights.y() * b + weights.z() * c;
}

/// The screen a stroke was drawn on: a camera and the image size its pixel coordinates refer to.
struct StrokeScreen {
  Camera camera;
  int width = 1024, height = 1024;  ///< pixels; x right, y down, (0, 0) the top-left corner
};

/// One recorded screen point that hit the mesh.
struct RecordedPoint {
  std::size_t screen_index = 0;     ///< index of the screen point it came from
  Index triangle = -1;              ///< hit triangle (index into mesh.triangles)
  Vec3 barycentric = Vec3::Zero();  ///< (s, r, t) of eq. 4.2
  Vec3 position = Vec3::Zero();     ///< eq. 4.1, mm
  Vec2 uv = Vec2::Zero();           ///< eq. 4.3 (u right, v up)
};

/// What recording a stroke gave: the stroke to paint and the points behind it.
struct RecordedStroke {
  WoundStroke stroke;                 ///< the hit points as surface points, with the brush radius
  std::vector<RecordedPoint> points;  ///< one per screen point that hit the mesh, in drawing order
  std::size_t missed = 0;             ///< screen points whose ray missed the mesh
};

/// Records a stroke drawn at `screen_points` (pixels of `screen`) on `mesh_with_uvs` with brush radius
/// `radius_mm`. Only the first hit along each ray counts (the visible surface). Throws InputError naming
/// "wound stroke" when the mesh has no UVs, a point is not finite, the screen size is not positive, or no
/// point hits the mesh.
RecordedStroke record_screen_stroke(const TriMesh& mesh_with_uvs, const StrokeScreen& screen,
                                    const std::vector<Vec2>& screen_points, double radius_mm);
/// The same with a ray caster built once on `mesh_with_uvs` (for several strokes on one mesh).
RecordedStroke record_screen_stroke(const TriMesh& mesh_with_uvs, const RayCaster& caster, const StrokeScreen& screen,
                                    const std::vector<Vec2>& screen_points, double radius_mm);

}  // namespace forensim
