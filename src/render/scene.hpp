#pragma once
/// A scene to render: meshes with materials (shared, not copied), lights, an environment, an optional
/// cut-away plane, and 3D overlays (line segments such as tissue-depth vectors, and landmark dots) that
/// are drawn over the shaded picture.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/tri_mesh.hpp"
#include "render/camera.hpp"
#include "render/light.hpp"
#include "render/surface_material.hpp"

namespace forensim {

/// Half-space removal: every point x with normal . (x - point) > 0 is cut away.
struct CutPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();
  /// Signed distance of x to the plane (positive on the removed side).
  double signed_distance(const Vec3& x) const { return normal.normalized().dot(x - point); }
};

struct RenderObject {
  std::shared_ptr<const TriMesh> mesh;
  SurfaceMaterial material;
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  ///< object to world (rigid or scaled)
  /// This object's own cut plane (in world coordinates); applies together with Scene::cutaway.
  std::optional<CutPlane> cutaway;
  bool use_scene_cutaway = true;  ///< false: the scene's cut plane leaves this object whole
  std::string name;
};

/// A 3D line segment overlay (world coordinates), drawn anti-aliased after shading.
struct LineOverlay {
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
  Vec4f colour = Vec4f(1.0f, 0.85f, 0.1f, 1.0f);  ///< display (sRGB) colour and alpha
  double width_px = 2.0;
  bool depth_test = true;  ///< drawn faint (20% alpha) where an opaque surface is in front
};

/// A 3D point overlay drawn as a dot (landmarks).
struct PointOverlay {
  Vec3 position = Vec3::Zero();
  Vec4f colour = Vec4f(0.9f, 0.15f, 0.1f, 1.0f);  ///< display (sRGB) colour and alpha
  double radius_px = 4.0;
  bool depth_test = true;  ///< drawn faint (25% alpha) where an opaque surface is in front
  std::string label;       ///< optional text drawn beside the dot
};

struct Scene {
  std::vector<RenderObject> objects;
  std::vector<Light> lights = studio_lights();
  Environment environment;
  std::optional<CutPlane> cutaway;
  Camera camera;
  std::vector<LineOverlay> lines;
  std::vector<PointOverlay> points;

  /// Adds `mesh` (shared) with `material`; returns the new object for further settings.
  RenderObject& add(std::shared_ptr<const TriMesh> mesh, const SurfaceMaterial& material, const std::string& name = "");
  /// Adds a copy of `mesh`.
  RenderObject& add(const TriMesh& mesh, const SurfaceMaterial& material, const std::string& name = "");
  /// World-space bounding box of all objects (after their transforms; ignoring cut planes).
  BoundingBox bounds() const;
  /// Bounding box of what remains visible after the cut planes: vertices on the kept side, plus the
  /// projections of removed vertices onto the plane that removed them (which contain the cross-section).
  BoundingBox visible_bounds() const;
  /// Points the camera at all objects from the named view for an image of the given aspect (width/height),
  /// and turns the environment's up to the subject's up.
  void frame(ViewName view, double aspect, const FramingOptions& options = {});
};

}  // namespace forensim
