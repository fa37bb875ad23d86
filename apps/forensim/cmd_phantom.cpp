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
#include "phantoms/phantom_surface.hpp"
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
};

int run_phantom(const PhantomArgs& a) {
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
      sub->add_option("name", a->name, "Phantom: arm or head")->check(CLI::IsMember(phantom_names()));
      sub->add_option("-o,--out", a->out, "Output folder");
      sub->add_option("--voxel", a->voxel_mm, "Sampling voxel size (mm): smaller = finer surfaces")
          ->check(CLI::Range(0.3, 10.0));
      sub->add_option("--smooth", a->smooth, "Taubin smoothing iterations")->check(CLI::Range(0, 200));
      sub->add_option("--format", a->format, "Mesh format")->check(CLI::IsMember({"glb", "obj", "ply", "stl"}));
      sub->add_option("--picture-size", a->picture_size, "Pixels per view")->check(CLI::Range(64, 4096));
      return [a]() { return run_phantom(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
