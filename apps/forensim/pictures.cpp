#include "pictures.hpp"

#include <spdlog/spdlog.h>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/tet_boundary.hpp"
#include "geometry/tet_cut.hpp"
#include "image/jpeg_io.hpp"
#include "image/png_io.hpp"
#include "render/renderer.hpp"

namespace forensim::cli {

SurfaceMaterial material_from_name(const std::string& name, const TriMesh& mesh, std::shared_ptr<const Image> texture) {
  if (name == "skin") return SurfaceMaterial::skin();
  if (name == "bone") return SurfaceMaterial::bone();
  if (name == "clay") return SurfaceMaterial::clay();
  if (name == "vertex") {
    if (!mesh.has_colors()) throw Error("material 'vertex': the mesh has no vertex colours", ErrorKind::usage);
    SurfaceMaterial m = SurfaceMaterial::clay();
    m.colour_source = ColourSource::vertex_colours;
    m.base_colour = Vec3f::Ones();
    return m;
  }
  if (name == "texture") {
    if (!texture || !mesh.has_uvs()) {
      throw Error("material 'texture': the mesh has no readable base colour texture or no UVs", ErrorKind::usage);
    }
    SurfaceMaterial m = SurfaceMaterial::skin(Vec3f::Ones());
    m.colour_source = ColourSource::texture;
    m.base_texture = std::move(texture);
    return m;
  }
  if (name.rfind("field:", 0) == 0) {
    const std::string field = name.substr(6);
    auto it = mesh.vertex_fields.scalars.find(field);
    if (it == mesh.vertex_fields.scalars.end() || it->second.empty()) {
      throw Error("material '" + name + "': the mesh has no per-vertex field '" + field + "'", ErrorKind::usage);
    }
    const auto [lo, hi] = std::minmax_element(it->second.begin(), it->second.end());
    return SurfaceMaterial::field(field, *lo, *hi > *lo ? *hi : *lo + 1.0);
  }
  throw Error("unknown material '" + name + "' (use skin, bone, clay, vertex, texture or field:NAME)",
              ErrorKind::usage);
}

SurfaceMaterial default_material(const TriMesh& mesh, std::shared_ptr<const Image> texture) {
  if (texture && mesh.has_uvs()) return material_from_name("texture", mesh, std::move(texture));
  if (mesh.has_colors()) return material_from_name("vertex", mesh);
  return SurfaceMaterial::clay();
}

std::shared_ptr<const Image> load_base_texture(const TriMesh& mesh) {
  const std::string& path = mesh.material.base_color_texture;
  if (path.empty()) return nullptr;
  try {
    return std::make_shared<const Image>(read_image(path));
  } catch (const Error& e) {
    spdlog::warn("texture {} not used: {}", path, e.what());
    return nullptr;
  }
}

void add_depth_vectors(Scene& scene, const std::vector<std::pair<Vec3, Vec3>>& skull_to_skin) {
  for (const auto& [skull, skin] : skull_to_skin) {
    LineOverlay line;
    line.from = skull;
    line.to = skin;
    scene.lines.push_back(line);
    PointOverlay dot;
    dot.position = skull;
    dot.radius_px = 2.5;
    scene.points.push_back(dot);
  }
}

Scene skin_over_bone_scene(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const TriMesh> bone,
                           double skin_opacity, const ViewAxes& axes) {
  Scene scene;
  scene.environment.up = axes.up;
  scene.add(std::move(bone), SurfaceMaterial::bone(), "bone");
  SurfaceMaterial skin_material = SurfaceMaterial::skin();
  skin_material.opacity = skin_opacity;
  scene.add(std::move(skin), skin_material, "skin");
  return scene;
}

Scene cutaway_scene(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const TriMesh> bone, const Vec3& cut_normal,
                    const ViewAxes& axes) {
  Scene scene;
  scene.environment.up = axes.up;
  const BoundingBox box = bounding_box(skin->positions);
  scene.add(std::move(bone), SurfaceMaterial::bone(), "bone");
  scene.add(std::move(skin), SurfaceMaterial::skin(), "skin");
  scene.cutaway = CutPlane{box.center(), cut_normal.normalized()};
  return scene;
}

Image render_view(Scene scene, const RenderSettings& settings, const std::string& view, const ViewAxes& axes) {
  FramingOptions framing;
  framing.axes = axes;
  scene.environment.up = axes.up;
  scene.frame(view_from_name(view), static_cast<double>(settings.width) / settings.height, framing);
  return render(scene, settings);
}

std::vector<SheetCell> phantom_view_cells(const std::string& phantom_name, std::shared_ptr<const TriMesh> skin,
                                          std::shared_ptr<const TriMesh> bone, const RenderSettings& settings) {
  // The arm lies along +x with the back of the hand up (+z) and the thumb toward +y.
  const bool arm = phantom_name == "arm";
  const ViewAxes axes = arm ? ViewAxes{Vec3::UnitZ(), Vec3::UnitY()} : ViewAxes{};
  Scene plain;
  plain.environment.up = axes.up;
  plain.add(skin, SurfaceMaterial::skin(), "skin");
  std::vector<SheetCell> cells;
  cells.push_back({render_view(plain, settings, arm ? "top" : "front", axes), arm ? "back of the hand" : "front"});
  cells.push_back({render_view(plain, settings, arm ? "front" : "left", axes), arm ? "thumb side" : "side"});
  cells.push_back(
      {render_view(skin_over_bone_scene(skin, bone, 0.3, axes), settings, "three_quarter", axes), "skin over bone"});
  // The cut removes the half the camera looks from: the back of the hand, or the subject's left.
  const Vec3 cut_normal = arm ? Vec3(Vec3::UnitZ()) : axes.left();
  cells.push_back({render_view(cutaway_scene(skin, bone, cut_normal, axes), settings, arm ? "top" : "left", axes),
                   "cut-away: bone inside flesh"});
  return cells;
}

Scene tet_cutaway_scene(const TetMesh& mesh, const Vec3& cut_normal, const ViewAxes& axes) {
  const TetMesh kept = tets_behind_plane(mesh, bounding_box(mesh.positions).center(), cut_normal);
  Scene scene;
  scene.environment.up = axes.up;
  auto flesh = std::make_shared<TriMesh>(tet_boundary_mesh(kept, tissue_flesh));
  double edge_sum = 0.0;
  for (const Tri& t : flesh->triangles)
    edge_sum +=
        (flesh->positions[static_cast<std::size_t>(t[0])] - flesh->positions[static_cast<std::size_t>(t[1])]).norm();
  const double mean_edge = flesh->triangles.empty() ? 1.0 : edge_sum / static_cast<double>(flesh->triangle_count());
  SurfaceMaterial flesh_material = SurfaceMaterial::skin(Vec3f(0.62f, 0.30f, 0.26f));
  flesh_material.wire_width_mm = 0.035 * mean_edge;
  flesh_material.crease_angle_deg = 0.0;
  scene.add(flesh, flesh_material, "flesh");
  auto bone = std::make_shared<TriMesh>(tet_boundary_mesh(kept, tissue_bone));
  if (bone->triangle_count() > 0) {
    SurfaceMaterial bone_material = SurfaceMaterial::bone();
    bone_material.wire_width_mm = flesh_material.wire_width_mm;
    bone_material.crease_angle_deg = 0.0;
    scene.add(bone, bone_material, "bone");
  }
  return scene;
}

BodyViews body_views(const std::string& kind, const ViewAxes& axes) {
  if (kind == "arm") {
    // The arm lies along +x with the back of the hand up (+z) and the thumb toward +y.
    const ViewAxes arm{Vec3::UnitZ(), Vec3::UnitY()};
    return {arm, "top", "back of the hand", "front", "thumb side", Vec3::UnitZ(), "top"};
  }
  return {axes, "front", "front", "left", "side", axes.left(), "left"};
}

std::vector<SheetCell> tet_model_cells(const BodyViews& views, std::shared_ptr<const TriMesh> skin,
                                       const TetMesh& volume, const RenderSettings& settings) {
  Scene plain;
  plain.environment.up = views.axes.up;
  plain.add(skin, SurfaceMaterial::skin(), "skin");
  std::vector<SheetCell> cells;
  cells.push_back({render_view(plain, settings, views.view_a, views.axes), views.caption_a});
  cells.push_back({render_view(plain, settings, views.view_b, views.axes), views.caption_b});
  cells.push_back(
      {render_view(tet_cutaway_scene(volume, views.cut_normal, views.axes), settings, views.cut_view, views.axes),
       "tets cut open: flesh and bone"});
  return cells;
}

std::vector<SheetCell> textured_arm_cells(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const Image> colour,
                                          std::shared_ptr<const Image> normal, const RenderSettings& settings) {
  const BodyViews views = body_views("arm");
  SurfaceMaterial material = SurfaceMaterial::skin(Vec3f::Ones());
  material.colour_source = ColourSource::texture;
  material.base_texture = colour;
  material.normal_map = std::move(normal);
  Scene scene;
  scene.environment.up = views.axes.up;
  scene.add(std::move(skin), material, "skin");
  std::vector<SheetCell> cells;
  cells.push_back({render_view(scene, settings, "top", views.axes), "back of the hand"});
  cells.push_back({render_view(scene, settings, "bottom", views.axes), "palm"});
  Image layout = colour->resized(settings.width, settings.height);
  cells.push_back({layout, "upper skin colour map (UV layout)"});
  return cells;
}

ViewAxes axes_from_name(const std::string& name) {
  if (name == "lps") return ViewAxes{};
  if (name == "yup") return ViewAxes{Vec3::UnitY(), Vec3::UnitZ()};
  throw Error("unknown axes '" + name + "' (use lps or yup)", ErrorKind::usage);
}

}  // namespace forensim::cli
