// forensim render: pictures of meshes (any format) as PNG: one view, several views on a sheet, or a
// turntable; materials by name, semi-transparent overlays, a cut-away plane.

#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_import.hpp"
#include "pictures.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"

namespace forensim::cli {
namespace {

struct RenderArgs {
  std::vector<std::string> meshes;
  std::vector<std::string> materials;
  std::vector<double> opacities;
  std::string output;
  std::vector<std::string> views{"three_quarter"};
  int turntable = 0;
  int size = 1024;
  int samples = 8;
  std::string cut;
  std::string axes = "lps";
  std::string unit = "auto";
  std::string title;
  std::uint64_t seed = 1;
};

// "x=12.5" or "-y=0": plane normal along the axis (negative with a leading minus), through that coordinate.
CutPlane parse_cut(const std::string& text) {
  const auto eq = text.find('=');
  std::string axis = text.substr(0, eq);
  double sign = 1.0;
  if (!axis.empty() && (axis[0] == '-' || axis[0] == '+')) {
    sign = axis[0] == '-' ? -1.0 : 1.0;
    axis = axis.substr(1);
  }
  if (eq == std::string::npos || axis.size() != 1 || std::string("xyz").find(axis[0]) == std::string::npos) {
    throw Error("--cut '" + text + "': expected AXIS=VALUE such as x=0 or -y=20", ErrorKind::usage);
  }
  double value = 0.0;
  try {
    value = std::stod(text.substr(eq + 1));
  } catch (const std::exception&) {
    throw Error("--cut '" + text + "': the value is not a number", ErrorKind::usage);
  }
  const int k = static_cast<int>(std::string("xyz").find(axis[0]));
  CutPlane plane;
  plane.normal = Vec3::Zero();
  plane.normal[k] = sign;
  plane.point = Vec3::Zero();
  plane.point[k] = value;
  return plane;
}

int run_render(const RenderArgs& a) {
  Stopwatch watch;
  Scene scene;
  const ViewAxes axes = axes_from_name(a.axes);
  if (!a.materials.empty() && a.materials.size() != a.meshes.size()) {
    throw Error("give one --material per mesh (" + std::to_string(a.meshes.size()) + ")", ErrorKind::usage);
  }
  if (!a.opacities.empty() && a.opacities.size() != a.meshes.size()) {
    throw Error("give one --opacity per mesh (" + std::to_string(a.meshes.size()) + ")", ErrorKind::usage);
  }
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    auto mesh = std::make_shared<TriMesh>(import_mesh(a.meshes[i], {a.unit, 0.0}));
    triangles += mesh->triangle_count();
    const auto texture = load_base_texture(*mesh);
    SurfaceMaterial material =
        a.materials.empty() ? default_material(*mesh, texture) : material_from_name(a.materials[i], *mesh, texture);
    if (!a.opacities.empty()) material.opacity = a.opacities[i];
    scene.add(std::shared_ptr<const TriMesh>(mesh), material, a.meshes[i]);
  }
  if (!a.cut.empty()) scene.cutaway = parse_cut(a.cut);
  scene.environment.up = axes.up;
  RenderSettings settings;
  settings.width = settings.height = a.size;
  settings.samples_per_pixel = a.samples;
  settings.seed = a.seed;
  FramingOptions framing;
  framing.axes = axes;

  std::vector<SheetCell> cells;
  if (a.turntable > 0) {
    const auto images = render_turntable(scene, settings, a.turntable, 10.0, framing);
    for (std::size_t i = 0; i < images.size(); ++i) {
      cells.push_back({images[i], std::to_string(static_cast<int>(360.0 * i / images.size())) + " deg"});
    }
  } else {
    std::vector<ViewName> views;
    for (const auto& v : a.views) views.push_back(view_from_name(v));
    const auto images = render_turntable(scene, settings, views, framing);
    for (std::size_t i = 0; i < images.size(); ++i) cells.push_back({images[i], a.views[i]});
  }
  const Image picture = cells.size() == 1 && a.title.empty()
                            ? cells[0].image
                            : make_sheet(cells, std::min<int>(static_cast<int>(cells.size()), 4), a.title);
  write_png(a.output, picture);
  std::printf("wrote %s (%dx%d, %s triangles, %s)\n", a.output.c_str(), picture.width(), picture.height(),
              format_count(triangles).c_str(), format_seconds(watch.seconds()).c_str());
  return 0;
}

const RegisterCommand render_command{
    "render", [](CLI::App& app) {
      auto* sub =
          app.add_subcommand("render", "Render meshes to a PNG picture (views, turntables, overlays, cut-aways)");
      auto a = std::make_shared<RenderArgs>();
      sub->add_option("meshes", a->meshes, "Meshes to draw, in any format Assimp reads")->required();
      sub->add_option("-o,--output", a->output, "PNG file to write")->required();
      sub->add_option("--material", a->materials, "Per mesh: skin, bone, clay, vertex, texture or field:NAME");
      sub->add_option("--opacity", a->opacities, "Per mesh opacity in [0,1] (semi-transparent overlays)")
          ->check(CLI::Range(0.0, 1.0));
      sub->add_option("--view", a->views,
                      "Views: front, back, left, right, top, bottom, three_quarter (several = sheet)")
          ->check(CLI::IsMember(view_names()));
      sub->add_option("--turntable", a->turntable, "Render N views around the subject on a sheet")
          ->check(CLI::Range(1, 72));
      sub->add_option("--size", a->size, "Picture width and height in pixels")->check(CLI::Range(16, 8192));
      sub->add_option("--samples", a->samples, "Samples per pixel")->check(CLI::Range(1, 1024));
      sub->add_option("--cut", a->cut, "Cut-away: remove the side AXIS > VALUE, e.g. x=0 (or -x=0 for the other side)");
      sub->add_option("--axes", a->axes, "Subject axes: lps (CT; z up, face -y) or yup (glTF/OBJ; y up, face +z)")
          ->check(CLI::IsMember({"lps", "yup"}));
      sub->add_option("--unit", a->unit, "Unit of the mesh files: auto, m, cm, mm or in");
      sub->add_option("--title", a->title, "Title over a sheet of views");
      sub->add_option("--seed", a->seed, "Sampling seed (same seed, same picture)");
      return [a]() { return run_render(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
