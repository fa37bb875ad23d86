// forensim phantom: the built-in body parts (arm, head) as skin and bone meshes with pictures.

#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "phantoms/forearm_uv.hpp"
#include "phantoms/phantom_surface.hpp"
#include "phantoms/skin_maps.hpp"
#include "pictures.hpp"
#include "render/sheet.hpp"

namespace forensim::cli {
namespace {

struct PhantomArgs {
  std::string name = "arm";
  std::string out = "out/phantom";
  double voxel_mm = 1.5;
  int smooth = 4;
  std::string format = "glb";
  int picture_size = 768;
  int resolution = 2048;
  std::uint64_t seed = 1;
};

/// forearm-uv: the arm's skin with a UV atlas and procedural skin maps (no bones: it is a painting surface).
int run_forearm_uv(const PhantomArgs& a) {
  RunFolder run(a.out, "phantom");
  run.set_job({{"name", a.name}, {"resolution", a.resolution}, {"seed", a.seed}, {"format", a.format}});
  ForearmUvOptions options;
  options.resolution = a.resolution;
  const ForearmUvModel model = make_forearm_uv(options);
  run.timings().add("surface", model.seconds_surface);
  run.timings().add("atlas", model.seconds_atlas);
  const SkinMaps maps = make_skin_maps(model.mesh, a.resolution, a.seed);
  run.timings().add("maps", maps.seconds);
  write_skin_maps(maps, run.path() / "maps");
  for (const char* map : {"epidermis", "dermis", "specular", "normal"})
    run.add_output(std::string("maps/") + map + ".png");
  TriMesh mesh = model.mesh;
  mesh.material.base_color_texture = (run.path() / "maps" / "epidermis.png").string();
  mesh.material.normal_texture = (run.path() / "maps" / "normal.png").string();
  const std::string file = "forearm-uv." + a.format;
  write_mesh(run.file(file), mesh);
  run.add_output(file);
  const ForearmUvStats& st = model.stats;
  run.facts()["skin"] = {{"vertices", mesh.vertex_count()},
                         {"triangles", mesh.triangle_count()},
                         {"charts", model.chart_names.size()},
                         {"l2_stretch", st.l2_stretch},
                         {"max_chart_l2_stretch", st.max_chart_l2_stretch},
                         {"packing_efficiency", st.packing_efficiency},
                         {"overlap_free", st.overlap_free},
                         {"hidden_seam_fraction", st.hidden_seam_fraction},
                         {"texel_mm", maps.texel_mm}};
  std::printf(
      "forearm-uv: %s triangles, %zu charts, L2 stretch %.3f (worst chart %.3f), packing %.0f %%, %s, "
      "%.0f %% of the seams hidden; maps %d^2 at %.3f mm per texel\n",
      format_count(mesh.triangle_count()).c_str(), model.chart_names.size(), st.l2_stretch, st.max_chart_l2_stretch,
      100.0 * st.packing_efficiency, st.overlap_free ? "no overlaps" : "OVERLAPS", 100.0 * st.hidden_seam_fraction,
      a.resolution, maps.texel_mm);
  Stopwatch watch;
  RenderSettings settings;
  settings.width = settings.height = a.picture_size;
  const auto cells =
      textured_arm_cells(std::make_shared<const TriMesh>(model.mesh), std::make_shared<const Image>(maps.epidermis),
                         std::make_shared<const Image>(maps.normal), settings);
  write_png(run.file("forearm-uv_views.png"), make_sheet(cells, 3, "forensim phantom: forearm-uv"));
  run.add_output("forearm-uv_views.png");
  run.timings().add("pictures", watch.seconds());
  run.write_record();
  std::printf("wrote %s\n", run.path().string().c_str());
  return 0;
}

int run_phantom(const PhantomArgs& a) {
  if (a.name == "forearm-uv") return run_forearm_uv(a);
  const auto phantom = make_phantom(a.name);
  RunFolder run(a.out, "phantom");
  run.set_job({{"name", a.name}, {"voxel_mm", a.voxel_mm}, {"smooth", a.smooth}, {"format", a.format}});
  Stopwatch watch;
  auto skin = std::make_shared<TriMesh>(phantom_surface(*phantom, PhantomSurface::skin, a.voxel_mm, a.smooth));
  auto bone = std::make_shared<TriMesh>(phantom_surface(*phantom, PhantomSurface::bone, a.voxel_mm, a.smooth));
  run.timings().add("surfaces", watch.seconds());
  for (const auto& [label, mesh] : {std::pair{"skin", skin}, std::pair{"bone", bone}}) {
    const std::string file = a.name + "_" + label + "." + a.format;
    write_mesh(run.file(file), *mesh);
    run.add_output(file);
  }
  for (const auto& [label, mesh] : {std::pair{"skin", skin}, std::pair{"bone", bone}}) {
    run.facts()[label] = {{"vertices", mesh->vertex_count()},
                          {"triangles", mesh->triangle_count()},
                          {"volume_mm3", enclosed_volume(*mesh)},
                          {"topology", check_topology(*mesh).summary()}};
    std::printf("%s %s: %s triangles, %.0f cm^3, %s\n", a.name.c_str(), label,
                format_count(mesh->triangle_count()).c_str(), enclosed_volume(*mesh) / 1000.0,
                check_topology(*mesh).summary().c_str());
  }
  watch.restart();
  RenderSettings settings;
  settings.width = settings.height = a.picture_size;
  const auto cells = phantom_view_cells(a.name, skin, bone, settings);
  write_png(run.file(a.name + "_views.png"), make_sheet(cells, 2, "forensim phantom: " + a.name));
  run.add_output(a.name + "_views.png");
  run.timings().add("pictures", watch.seconds());
  run.write_record();
  std::printf("wrote %s\n", run.path().string().c_str());
  return 0;
}

const RegisterCommand phantom_command{
    "phantom", [](CLI::App& app) {
      auto* sub = app.add_subcommand("phantom",
                                     "Write a built-in body part (arm, head) as skin and bone meshes, with pictures");
      auto a = std::make_shared<PhantomArgs>();
      std::vector<std::string> names = phantom_names();
      names.push_back("forearm-uv");
      sub->add_option("name", a->name, "Phantom: arm, head or forearm-uv (skin with UVs and skin maps)")
          ->check(CLI::IsMember(names));
      sub->add_option("-o,--out", a->out, "Output folder");
      sub->add_option("--voxel", a->voxel_mm, "Sampling voxel size (mm): smaller = finer surfaces")
          ->check(CLI::Range(0.3, 10.0));
      sub->add_option("--smooth", a->smooth, "Taubin smoothing iterations")->check(CLI::Range(0, 200));
      sub->add_option("--format", a->format, "Mesh format")->check(CLI::IsMember({"glb", "obj", "ply", "stl"}));
      sub->add_option("--picture-size", a->picture_size, "Pixels per view")->check(CLI::Range(64, 4096));
      sub->add_option("--resolution", a->resolution, "forearm-uv: skin map size (texels per side)")
          ->check(CLI::Range(64, 8192));
      sub->add_option("--seed", a->seed, "forearm-uv: seed of the skin maps' noise");
      return [a]() { return run_phantom(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
