#pragma once
/// Cameras for result pictures: perspective (vertical field of view) or orthographic, placed with
/// look_at, or framed automatically around a bounding box from a named view (front, left, three-quarter).
/// Image coordinates: x right, y down, (0,0) the top-left corner of the top-left pixel.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/bounding_box.hpp"

namespace forensim {

/// A ray: origin and unit direction.
struct Ray3 {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
};

enum class ProjectionKind { perspective, orthographic };

class Camera {
 public:
  /// A perspective camera at (0, -1000, 0) mm looking at the origin with +Z up.
  Camera();
  /// Perspective camera at `eye` looking at `target`; `up` need not be orthogonal to the view direction
  /// (it is projected); `vertical_fov_deg` is the full vertical field of view in degrees (0, 180).
  /// Throws InputError when eye == target, up is parallel to the view direction or the fov is out of range.
  static Camera look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double vertical_fov_deg = 30.0);
  /// Orthographic camera: parallel rays along target - eye; `view_height` is the height of the visible
  /// region in scene units (mm).
  static Camera orthographic(const Vec3& eye, const Vec3& target, const Vec3& up, double view_height);

  /// Primary ray through image point (px, py) in pixels of a width x height image.
  Ray3 ray(double px, double py, int width, int height) const;
  /// Projects a world point into a width x height image. Returns false when the point is behind the
  /// camera; else sets `pixel` (continuous pixel coordinates) and `depth` (distance along the view axis).
  bool project(const Vec3& point, int width, int height, Vec2* pixel, double* depth) const;

  const Vec3& eye() const { return m_eye; }
  const Vec3& target() const { return m_target; }
  /// Orthonormal camera frame: forward (towards the target), right and up (image up).
  const Vec3& forward() const { return m_forward; }
  const Vec3& right() const { return m_right; }
  const Vec3& up() const { return m_up; }
  ProjectionKind projection() const { return m_projection; }
  double vertical_fov_deg() const { return m_fov_deg; }
  double view_height() const { return m_view_height; }

 private:
  Vec3 m_eye, m_target, m_forward, m_right, m_up;
  ProjectionKind m_projection = ProjectionKind::perspective;
  double m_fov_deg = 30.0;
  double m_tan_half_fov = 0.0;  // tan(fov / 2), cached for ray generation
  double m_view_height = 100.0;
};

/// The subject's anatomical axes in scene coordinates: `up` (superior) and `front` (anterior, the way
/// the face looks). The default is the LPS convention of CT scans: +Z superior, -Y anterior (so +X is
/// the subject's left). For Y-up meshes facing +Z (glTF, most OBJ heads) use {+Y, +Z}.
struct ViewAxes {
  Vec3 up = Vec3::UnitZ();
  Vec3 front = -Vec3::UnitY();
  /// The subject's left: up x front.
  Vec3 left() const { return up.cross(front).normalized(); }
};

/// Named views: the camera looks at the subject from its front, back, left side, right side, above,
/// below, or a three-quarter view (40 degrees towards the subject's left, 15 degrees above).
enum class ViewName { front, back, left, right, top, bottom, three_quarter };

/// View by name ("front", "back", "left", "right", "top", "bottom", "three_quarter"); throws InputError.
ViewName view_from_name(const std::string& name);
std::string to_string(ViewName view);
/// All view names in ViewName order.
std::vector<std::string> view_names();

/// Framing of a bounding box.
struct FramingOptions {
  ViewAxes axes;
  double vertical_fov_deg = 30.0;  ///< perspective field of view
  double margin = 1.08;            ///< 1 = box corners touch the image border
  bool orthographic = false;
};

/// Camera that shows all of `box` from the named view, for an image of aspect ratio width/height.
Camera frame_view(const BoundingBox& box, ViewName view, double aspect, const FramingOptions& options = {});
/// Camera on a circle around `box`: azimuth from the front towards the subject's left (0 = front, 90 =
/// left side, 180 = back), elevation above the horizontal plane, both in degrees.
Camera orbit_view(const BoundingBox& box, double azimuth_deg, double elevation_deg, double aspect,
                  const FramingOptions& options = {});

}  // namespace forensim
