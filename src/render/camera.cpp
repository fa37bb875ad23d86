#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace forensim {
namespace {

constexpr double degrees = std::numbers::pi / 180.0;

void set_frame(const Vec3& eye, const Vec3& target, const Vec3& up, Vec3* forward, Vec3* right, Vec3* image_up) {
  const Vec3 d = target - eye;
  require_input(d.allFinite() && d.norm() > 0.0, "camera", "", "eye and target must be distinct finite points");
  *forward = d.normalized();
  const Vec3 r = forward->cross(up);
  require_input(up.allFinite() && r.norm() > 1e-9 * up.norm() && up.norm() > 0.0, "camera", "",
                "up vector is zero or parallel to the view direction");
  *right = r.normalized();
  *image_up = right->cross(*forward);
}

Vec3 direction_of(double azimuth_deg, double elevation_deg, const ViewAxes& axes) {
  const Vec3 up = axes.up.normalized();
  const Vec3 front = (axes.front - axes.front.dot(up) * up).normalized();
  const Vec3 left = up.cross(front);
  const double a = azimuth_deg * degrees, e = elevation_deg * degrees;
  return std::cos(e) * (std::cos(a) * front + std::sin(a) * left) + std::sin(e) * up;
}

}  // namespace

Camera::Camera() : m_eye(0, -1000, 0), m_target(Vec3::Zero()), m_tan_half_fov(std::tan(15.0 * degrees)) {
  set_frame(m_eye, m_target, Vec3::UnitZ(), &m_forward, &m_right, &m_up);
}

Camera Camera::look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double vertical_fov_deg) {
  require_input(vertical_fov_deg > 0.0 && vertical_fov_deg < 180.0, "camera", "vertical_fov_deg",
                "field of view must be in (0, 180) degrees, got " + std::to_string(vertical_fov_deg));
  Camera c;
  c.m_eye = eye;
  c.m_target = target;
  set_frame(eye, target, up, &c.m_forward, &c.m_right, &c.m_up);
  c.m_projection = ProjectionKind::perspective;
  c.m_fov_deg = vertical_fov_deg;
  c.m_tan_half_fov = std::tan(0.5 * vertical_fov_deg * degrees);
  return c;
}

Camera Camera::orthographic(const Vec3& eye, const Vec3& target, const Vec3& up, double view_height) {
  require_input(view_height > 0.0 && std::isfinite(view_height), "camera", "view_height",
                "must be positive, got " + std::to_string(view_height));
  Camera c = look_at(eye, target, up, 30.0);
  c.m_projection = ProjectionKind::orthographic;
  c.m_view_height = view_height;
  return c;
}

Ray3 Camera::ray(double px, double py, int width, int height) const {
  const double sx = 2.0 * px / width - 1.0;   // -1 left .. 1 right
  const double sy = 1.0 - 2.0 * py / height;  // -1 bottom .. 1 top
  const double aspect = static_cast<double>(width) / height;
  Ray3 r;
  if (m_projection == ProjectionKind::perspective) {
    const double t = m_tan_half_fov;
    r.origin = m_eye;
    r.direction = (m_forward + sx * t * aspect * m_right + sy * t * m_up).normalized();
  } else {
    const double half = 0.5 * m_view_height;
    r.origin = m_eye + sx * half * aspect * m_right + sy * half * m_up;
    r.direction = m_forward;
  }
  return r;
}

bool Camera::project(const Vec3& point, int width, int height, Vec2* pixel, double* depth) const {
  const Vec3 d = point - m_eye;
  const double z = d.dot(m_forward);
  const double aspect = static_cast<double>(width) / height;
  double sx, sy;
  if (m_projection == ProjectionKind::perspective) {
    if (z <= 1e-12) return false;
    const double t = std::tan(0.5 * m_fov_deg * degrees);
    sx = d.dot(m_right) / (z * t * aspect);
    sy = d.dot(m_up) / (z * t);
  } else {
    const double half = 0.5 * m_view_height;
    sx = d.dot(m_right) / (half * aspect);
    sy = d.dot(m_up) / half;
  }
  *pixel = Vec2(0.5 * (sx + 1.0) * width, 0.5 * (1.0 - sy) * height);
  *depth = z;
  return true;
}

ViewName view_from_name(const std::string& name) {
  const std::vector<std::string> names = view_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<ViewName>(i);
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError("view", "", "unknown view '" + name + "' (known: " + known + ")");
}

std::string to_string(ViewName view) {
  return view_names()[static_cast<std::size_t>(view)];
}

std::vector<std::string> view_names() {
  return {"front", "back", "left", "right", "top", "bottom", "three_quarter"};
}

Camera orbit_view(const BoundingBox& box, double azimuth_deg, double elevation_deg, double aspect,
                  const FramingOptions& options) {
  require_input(!box.empty() && box.min.allFinite() && box.max.allFinite(), "camera framing", "",
                "empty or non-finite bounding box");
  require_input(aspect > 0.0 && std::isfinite(aspect), "camera framing", "aspect", "must be positive");
  const Vec3 to_eye = direction_of(azimuth_deg, elevation_deg, options.axes);
  Vec3 up = options.axes.up.normalized();
  if (std::abs(to_eye.dot(up)) > 0.999) {
    // Looking straight down or up: the subject's front is image up (down for the view from below).
    const Vec3 front = options.axes.front.normalized();
    up = to_eye.dot(up) > 0 ? front : Vec3(-front);
  }
  const Vec3 center = box.center();
  const double diagonal = std::max(box.diagonal(), 1e-9);
  // Frame from a provisional camera: corner offsets across (x, y) and along (z, towards the eye) the view.
  Camera probe = Camera::look_at(center + to_eye * diagonal, center, up, options.vertical_fov_deg);
  double need_distance = 0.0, need_height = 0.0;
  const double tan_v = std::tan(0.5 * options.vertical_fov_deg * degrees);
  const double tan_h = tan_v * aspect;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? box.max[0] : box.min[0], (i & 2) ? box.max[1] : box.min[1],
                      (i & 4) ? box.max[2] : box.min[2]);
    const Vec3 d = corner - center;
    const double x = std::abs(d.dot(probe.right())), y = std::abs(d.dot(probe.up())), z = d.dot(to_eye);
    need_distance = std::max({need_distance, z + options.margin * x / tan_h, z + options.margin * y / tan_v});
    need_height = std::max({need_height, 2.0 * options.margin * y, 2.0 * options.margin * x / aspect});
  }
  if (options.orthographic)
    return Camera::orthographic(center + to_eye * (need_distance + diagonal), center, up, std::max(need_height, 1e-9));
  return Camera::look_at(center + to_eye * std::max(need_distance, 1e-6 * diagonal), center, up,
                         options.vertical_fov_deg);
}

Camera frame_view(const BoundingBox& box, ViewName view, double aspect, const FramingOptions& options) {
  switch (view) {
    case ViewName::front:
      return orbit_view(box, 0, 0, aspect, options);
    case ViewName::back:
      return orbit_view(box, 180, 0, aspect, options);
    case ViewName::left:
      return orbit_view(box, 90, 0, aspect, options);
    case ViewName::right:
      return orbit_view(box, -90, 0, aspect, options);
    case ViewName::top:
      return orbit_view(box, 0, 90, aspect, options);
    case ViewName::bottom:
      return orbit_view(box, 0, -90, aspect, options);
    case ViewName::three_quarter:
      return orbit_view(box, 40, 15, aspect, options);
  }
  return orbit_view(box, 0, 0, aspect, options);
}

}  // namespace forensim
