#include "render/quick_render.hpp"

#include "render/renderer.hpp"
#include "render/scene.hpp"

namespace forensim {

Image render_mesh(const TriMesh& mesh, const RenderSettings& settings, const std::string& view, const ViewAxes& axes) {
  const ViewName name = view_from_name(view);
  Scene scene;
  SurfaceMaterial material = SurfaceMaterial::clay();
  if (mesh.has_colors()) {
    material.colour_source = ColourSource::vertex_colours;
    material.base_colour = Vec3f(1, 1, 1);
  }
  scene.add(mesh, material, "mesh");
  scene.environment.up = axes.up;
  FramingOptions framing;
  framing.axes = axes;
  scene.frame(name, static_cast<double>(settings.width) / settings.height, framing);
  return render(scene, settings);
}

}  // namespace forensim
