// forensim convert: mesh format conversion with unit handling, repair, remeshing and decimation, so scans
// and exports from other tools become clean millimetre meshes (and tet meshes move between Gmsh, TetGen
// and ParaView).

#include <spdlog/spdlog.h>

#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "mesh_processing/decimate.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "mesh_processing/repair_mesh.hpp"

namespace forensim::cli {
namespace {

struct ConvertArgs {
  std::string input, output, unit = "auto";
  bool repair = false;
  std::size_t max_hole_edges = 500;
  double remesh_mm = 0.0;
  std::size_t decimate = 0;
  int largest = 0;
};

int run_convert(const ConvertArgs& a) {
  const DataKind in_kind = classify_path(a.input);
  if (in_kind == DataKind::volume) {
    throw Error(a.input + ": is a volume; use `forensim isosurface` to make a mesh from it", ErrorKind::usage);
  }
  if (in_kind == DataKind::tet_mesh) {
    if (a.repair || a.remesh_mm > 0 || a.decimate > 0 || a.largest > 0) {
      throw Error("--repair, --remesh, --decimate and --largest apply to surface meshes only", ErrorKind::usage);
    }
    const TetMesh mesh = read_tet_mesh(a.input);
    write_tet_mesh(a.output, mesh);
    std::printf("%s: %zu nodes, %zu tets\n", a.output.c_str(), mesh.vertex_count(), mesh.tet_count());
    return 0;
  }
  Stopwatch watch;
  TriMesh mesh = import_mesh(a.input, {a.unit, 0.0});
  std::printf("read %s: %zu vertices, %zu triangles, %s\n", a.input.c_str(), mesh.vertex_count(), mesh.triangle_count(),
              check_topology(mesh).summary().c_str());
  if (a.largest > 0) mesh = keep_largest_components(mesh, a.largest);
  if (a.repair) {
    RepairOptions options;
    options.max_hole_edges = a.max_hole_edges;
    const RepairReport report = repair_mesh(mesh, options);
    std::printf("repaired: %s\n", report.after.summary().c_str());
  }
  if (a.remesh_mm > 0) mesh = remesh_isotropic(mesh, a.remesh_mm);
  if (a.decimate > 0) mesh = decimate(mesh, a.decimate);
  // A mesh whose triangles are all degenerate (every vertex at one point, say) repairs to nothing: no output.
  require_input(mesh.triangle_count() > 0, a.input, "", "no triangles are left after the options applied");
  if (!mesh.has_normals() || a.remesh_mm > 0 || a.decimate > 0) compute_normals(mesh);
  write_mesh(a.output, mesh);
  std::printf("wrote %s: %zu vertices, %zu triangles, %s (%s)\n", a.output.c_str(), mesh.vertex_count(),
              mesh.triangle_count(), format_size_mm(bounding_box(mesh.positions).size()).c_str(),
              format_seconds(watch.seconds()).c_str());
  return 0;
}

const RegisterCommand convert_command{
    "convert", [](CLI::App& app) {
      auto* sub = app.add_subcommand("convert",
                                     "Convert meshes between formats (in millimetres), optionally repairing, "
                                     "remeshing or decimating them");
      auto a = std::make_shared<ConvertArgs>();
      sub->add_option("input", a->input, "Surface mesh (any Assimp format) or tet mesh (.msh, .node/.ele, .vtu)")
          ->required();
      sub->add_option("output", a->output, "Output: .obj, .ply, .stl, .glb, .gltf, or .msh/.node/.vtu for tet meshes")
          ->required();
      sub->add_option("--unit", a->unit, "Unit of the input file: auto, m, cm, mm or in");
      sub->add_flag("--repair", a->repair, "Remove degenerate/duplicate triangles, stitch, orient, fill holes");
      sub->add_option("--max-hole-edges", a->max_hole_edges,
                      "With --repair: leave holes with more boundary edges open");
      sub->add_option("--remesh", a->remesh_mm, "Isotropic remeshing to this edge length (mm)")
          ->check(CLI::PositiveNumber);
      sub->add_option("--decimate", a->decimate, "Decimate to at most this many triangles")->check(CLI::PositiveNumber);
      sub->add_option("--largest", a->largest, "Keep only the N largest connected components")
          ->check(CLI::PositiveNumber);
      return [a]() { return run_convert(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
