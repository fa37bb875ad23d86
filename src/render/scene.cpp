#include "render/scene.hpp"

#include "core/error.hpp"

namespace forensim {

RenderObject& Scene::add(std::shared_ptr<const TriMesh> mesh, const SurfaceMaterial& material,
                         const std::string& name) {
  require_input(mesh != nullptr, "scene", name, "null mesh");
  RenderObject object;
  object.mesh = std::move(mesh);
  object.material = material;
  object.name = name.empty() ? "object " + std::to_string(objects.size()) : name;
  objects.push_back(std::move(object));
  return objects.back();
}

RenderObject& Scene::add(const TriMesh& mesh, const SurfaceMaterial& material, const std::string& name) {
  return add(std::make_shared<const TriMesh>(mesh), material, name);
}

BoundingBox Scene::bounds() const {
  BoundingBox box;
  for (const RenderObject& object : objects) {
    if (!object.mesh) continue;
    for (const Vec3& p : object.mesh->positions) box.extend(object.transform * p);
  }
  return box;
}

BoundingBox Scene::visible_bounds() const {
  BoundingBox box;
  for (const RenderObject& object : objects) {
    if (!object.mesh) continue;
    std::vector<CutPlane> planes;
    if (cutaway && object.use_scene_cutaway) planes.push_back(*cutaway);
    if (object.cutaway) planes.push_back(*object.cutaway);
    for (const Vec3& local : object.mesh->positions) {
      Vec3 p = object.transform * local;
      for (const CutPlane& plane : planes) {
        const double n = plane.normal.norm();
        if (!(n > 0)) continue;
        const double d = plane.signed_distance(p);
        if (d > 0) p -= d * plane.normal / n;
      }
      box.extend(p);
    }
  }
  return box;
}

void Scene::frame(ViewName view, double aspect, const FramingOptions& options) {
  const BoundingBox visible = visible_bounds();
  camera = frame_view(visible.empty() ? bounds() : visible, view, aspect, options);
  environment.up = options.axes.up;
}

}  // namespace forensim
