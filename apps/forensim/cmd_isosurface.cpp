// forensim isosurface: closed, oriented surfaces from CT and other volumes (skin at 500, bone at 1150 for
// CT stored as HU + 1024), with the built-in CT head phantom as the default input.

#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "mesh_processing/decimate.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "pictures.hpp"
#include "volume/iso_surface.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

struct IsoArgs {
  std::string input;
  std::vector<double> iso_values;
  std::vector<std::string> outputs;
  int largest = 0;
  int smooth = 0;
  double resample = 1.0;
  std::size_t decimate = 0;
  std::string render;
  double phantom_voxel_mm = 2.0;
};

int run_isosurface(const IsoArgs& a) {
  if (a.iso_values.size() != a.outputs.size()) {
    throw Error("give one --out per --iso (" + std::to_string(a.iso_values.size()) + " iso-values, " +
                    std::to_string(a.outputs.size()) + " outputs)",
                ErrorKind::usage);
  }
  Stopwatch watch;
  ScalarGrid grid;
  if (a.input.empty()) {
    grid = make_ct_head_phantom({a.phantom_voxel_mm, 20.0, 1});
    std::printf("input: built-in CT head phantom (%d x %d x %d at %.1f mm)\n", grid.nx, grid.ny, grid.nz,
                a.phantom_voxel_mm);
  } else {
    grid = read_volume(a.input);
    std::printf("input: %s (%d x %d x %d, spacing %.2f x %.2f x %.2f mm)\n", a.input.c_str(), grid.nx, grid.ny, grid.nz,
                grid.spacing.x(), grid.spacing.y(), grid.spacing.z());
  }
  IsoSurfaceOptions options;
  options.keep_largest_components = a.largest;
  options.smoothing_iterations = a.smooth;
  options.resample_factor = a.resample;
  std::vector<std::shared_ptr<const TriMesh>> meshes;
  for (std::size_t i = 0; i < a.iso_values.size(); ++i) {
    TriMesh mesh = extract_iso_surface(grid, a.iso_values[i], options);
    if (mesh.triangle_count() == 0) {
      throw InputError(a.input.empty() ? "CT phantom" : a.input, "iso-value " + std::to_string(a.iso_values[i]),
                       "no sample lies above the iso-value; nothing to extract");
    }
    if (a.decimate > 0 && mesh.triangle_count() > a.decimate) {
      mesh = decimate(mesh, a.decimate);
      compute_normals(mesh);
    }
    write_mesh(a.outputs[i], mesh);
    std::printf("iso %g -> %s: %s triangles, %s, %s\n", a.iso_values[i], a.outputs[i].c_str(),
                format_count(mesh.triangle_count()).c_str(),
                format_size_mm(bounding_box(mesh.positions).size()).c_str(), check_topology(mesh).summary().c_str());
    meshes.push_back(std::make_shared<const TriMesh>(std::move(mesh)));
  }
  if (!a.render.empty()) {
    RenderSettings settings;
    settings.width = settings.height = 1024;
    Scene scene;
    if (meshes.size() >= 2) {
      // Lowest iso-value (skin) semi-transparent over the next (bone).
      scene = skin_over_bone_scene(meshes[0], meshes[1], 0.35, ViewAxes{});
    } else {
      scene.add(meshes[0], SurfaceMaterial::clay());
    }
    write_png(a.render, render_view(scene, settings, "three_quarter", ViewAxes{}));
    std::printf("picture: %s\n", a.render.c_str());
  }
  std::printf("done in %s\n", format_seconds(watch.seconds()).c_str());
  return 0;
}

const RegisterCommand isosurface_command{
    "isosurface", [](CLI::App& app) {
      auto* sub = app.add_subcommand("isosurface", "Extract closed surfaces from a CT or other volume at iso-values");
      auto a = std::make_shared<IsoArgs>();
      sub->add_option("volume", a->input,
                      "Volume (.nrrd, .nhdr, .mhd, .mha, DICOM folder); default: built-in CT phantom");
      sub->add_option("--iso", a->iso_values, "Iso-value(s); e.g. 500 for skin, 1150 for bone in HU+1024 CT")
          ->required();
      sub->add_option("-o,--out", a->outputs, "Output mesh per iso-value (.obj, .ply, .stl, .glb)")->required();
      sub->add_option("--largest", a->largest, "Keep the N largest components of each surface")
          ->check(CLI::Range(1, 1000));
      sub->add_option("--smooth", a->smooth, "Taubin smoothing iterations")->check(CLI::Range(0, 1000));
      sub->add_option("--resample", a->resample, "Extract from a grid this many times coarser (> 1) for speed")
          ->check(CLI::Range(0.25, 16.0));
      sub->add_option("--decimate", a->decimate, "Decimate each surface to at most this many triangles");
      sub->add_option("--render", a->render, "Also write a PNG picture (first surface over the second)");
      sub->add_option("--phantom-voxel", a->phantom_voxel_mm, "Voxel size of the built-in phantom (mm)")
          ->check(CLI::Range(0.5, 10.0));
      return [a]() { return run_isosurface(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
