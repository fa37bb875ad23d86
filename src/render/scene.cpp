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

void Scene::frame(ViewName view, double aspect, const FramingOptions& options) {
  camera = frame_view(bounds(), view, aspect, options);
  environment.up = options.axes.up;
}

}  // namespace forensim
