#include "desiccation/desiccation_pictures.hpp"

#include <memory>

#include "geometry/bounding_box.hpp"
#include "geometry/tet_boundary.hpp"
#include "geometry/tet_cut.hpp"
#include "render/colour_bar.hpp"
#include "render/renderer.hpp"
#include "render/scene.hpp"

namespace forensim {

namespace {

/// The tets of `model` at `positions`, all of them or those behind the cut plane through the centre.
TetMesh posed_volume(const DesiccationModel& model, const std::vector<Vec3>& positions, const Vec3* cut_normal) {
  const TetMesh& rest = model.body.volume;
  TetMesh posed;
  posed.positions = positions;
  if (cut_normal == nullptr) {
    posed.tets = rest.tets;
    posed.tet_labels = rest.tet_labels;
    return posed;
  }
  // Chosen on the rest shape, so the same tets show at every frame.
  TetMesh kept = tets_behind_plane(rest, bounding_box(rest.positions).center(), *cut_normal);
  posed.tets = std::move(kept.tets);
  posed.tet_labels = std::move(kept.tet_labels);
  return posed;
}

Image finish(Scene scene, const DesiccationViews& views, ViewName view, const RenderSettings& settings) {
  FramingOptions framing;
  framing.axes = views.axes;
  scene.environment.up = views.axes.up;
  scene.frame(view, static_cast<double>(settings.width) / settings.height, framing);
  return render(scene, settings);
}

}  // namespace

DesiccationViews desiccation_views(const std::string& layout, const ViewAxes& axes) {
  DesiccationViews v;
  v.axes = axes;
  v.cut_normal = axes.up;
  if (layout == "arm") return v;
  v.outside = ViewName::left;
  v.cut_normal = axes.left();
  v.cut = ViewName::left;
  return v;
}

Image render_moisture(const DesiccationModel& model, const DesiccationState& state, const DesiccationViews& views,
                      bool cut, const RenderSettings& settings) {
  const TetMesh posed = posed_volume(model, state.positions, cut ? &views.cut_normal : nullptr);
  std::vector<Index> node_of_vertex;
  auto flesh = std::make_shared<TriMesh>(tet_boundary_mesh(posed, tissue_flesh, nullptr, &node_of_vertex));
  std::vector<double>& dryness = flesh->vertex_fields.scalars["dryness"];
  dryness.resize(node_of_vertex.size());
  const double x0 = model.settings.tissue.initial_moisture;
  for (std::size_t i = 0; i < node_of_vertex.size(); ++i)
    dryness[i] = 1.0 - state.node_moisture[static_cast<std::size_t>(node_of_vertex[i])] / x0;
  Scene scene;
  SurfaceMaterial material = SurfaceMaterial::field("dryness", 0.0, 1.0, ColormapName::blue_white_red);
  material.crease_angle_deg = 0.0;
  scene.add(flesh, material, "flesh");
  auto bone = std::make_shared<TriMesh>(tet_boundary_mesh(posed, tissue_bone));
  if (bone->triangle_count() > 0) scene.add(bone, SurfaceMaterial::bone(), "bone");
  ColourBar bar;
  bar.colormap = Colormap(ColormapName::blue_white_red);
  bar.title = "water lost";
  bar.unit = "1 - X/X0";
  return with_colour_bar(finish(std::move(scene), views, cut ? views.cut : views.outside, settings), bar);
}

Image render_shrinkage(const DesiccationModel& model, const DesiccationState& state, const DesiccationViews& views,
                       const RenderSettings& settings) {
  Scene scene;
  const TetMesh now = posed_volume(model, state.positions, nullptr);
  scene.add(std::make_shared<TriMesh>(tet_boundary_mesh(now)), SurfaceMaterial::skin(), "shrunken");
  SurfaceMaterial ghost = SurfaceMaterial::clay();
  ghost.opacity = 0.3;
  scene.add(std::make_shared<TriMesh>(tet_boundary_mesh(model.body.volume)), ghost, "original");
  return finish(std::move(scene), views, views.outside, settings);
}

}  // namespace forensim
