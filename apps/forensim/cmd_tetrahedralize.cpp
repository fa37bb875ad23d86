// forensim tetrahedralize: a labelled (flesh/bone), surface-conforming tet mesh of a body part from skin and
// bone surfaces, a CT volume or a built-in phantom, with quality statistics and an optional cut-away picture.

#include <cmath>
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/tet_boundary.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_import.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "pictures.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

struct TetArgs {
  std::string skin, unit = "auto", ct, phantom = "arm", output, render;
  std::vector<std::string> bones;
  double skin_iso = 500.0, bone_iso = 1150.0;
  double edge = 0.0;
  std::size_t nodes = 0;
  bool paper = false;
  double radius_edge = 2.0;
  double min_dihedral = 12.0;
  double phantom_voxel_mm = 2.0;
};

/// The tets on the kept side of a plane through the mesh's centre (normal +z), as flesh and bone
/// boundary surfaces whose faces on the cut show the tets.
Scene cut_scene(const TetMesh& mesh) {
  BoundingBox box = bounding_box(mesh.positions);
  const Vec3 centre = box.center();
  TetMesh kept;
  kept.positions = mesh.positions;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    Vec3 c = Vec3::Zero();
    for (Index v : mesh.tets[t]) c += mesh.positions[static_cast<std::size_t>(v)] / 4.0;
    if (c.z() <= centre.z()) {
      kept.tets.push_back(mesh.tets[t]);
      kept.tet_labels.push_back(mesh.label(t));
    }
  }
  Scene scene;
  scene.add(tet_boundary_mesh(kept, tissue_flesh), SurfaceMaterial::skin(), "flesh");
  const TriMesh bone = tet_boundary_mesh(kept, tissue_bone);
  if (bone.triangle_count() > 0) scene.add(bone, SurfaceMaterial::bone(), "bone");
  return scene;
}

int run_tetrahedralize(const TetArgs& a) {
  Stopwatch watch;
  TetrahedralizeOptions options;
  options.edge_length_mm = a.edge;
  options.target_nodes = a.nodes;
  options.radius_edge_bound = a.radius_edge;
  options.min_dihedral_deg = a.min_dihedral;
  TetrahedralizeReport report;
  TetMesh mesh;
  if (!a.ct.empty()) {
    const ScalarGrid grid = read_volume(a.ct);
    std::printf("input: CT %s (%d x %d x %d), skin iso %g, bone iso %g\n", a.ct.c_str(), grid.nx, grid.ny, grid.nz,
                a.skin_iso, a.bone_iso);
    if (a.paper) throw Error("--paper needs --phantom arm or head", ErrorKind::usage);
    if (a.edge <= 0.0 && a.nodes == 0) throw Error("give --edge or --nodes", ErrorKind::usage);
    mesh = tetrahedralize_ct(grid, a.skin_iso, a.bone_iso, options, &report);
  } else {
    TriMesh skin;
    std::vector<TriMesh> bones;
    if (!a.skin.empty()) {
      skin = import_mesh(a.skin, {a.unit, 0.0});
      for (const std::string& bone : a.bones) bones.push_back(import_mesh(bone, {a.unit, 0.0}));
      std::printf("input: skin %s, %zu bone surface(s)\n", a.skin.c_str(), bones.size());
      if (a.paper) throw Error("--paper needs --phantom arm or head", ErrorKind::usage);
    } else {
      const auto phantom = make_phantom(a.phantom);
      skin = phantom_surface(*phantom, PhantomSurface::skin, a.phantom_voxel_mm);
      bones.push_back(phantom_surface(*phantom, PhantomSurface::bone, 0.75 * a.phantom_voxel_mm));
      std::printf("input: %s phantom (surfaces at %.2f mm voxels)\n", a.phantom.c_str(), a.phantom_voxel_mm);
      if (a.paper) options.target_nodes = paper_target_nodes(a.phantom);
    }
    if (options.edge_length_mm <= 0.0 && options.target_nodes == 0) options.edge_length_mm = 8.0;
    mesh = tetrahedralize(skin, bones, options, &report);
  }
  const TetQualityReport quality = tet_quality(mesh);
  // Tet labels travel as the writers' region array (`label` in VTU); quality goes beside them.
  mesh.tet_fields.scalars["radius_edge_ratio"] = quality.radius_edge_ratio;
  for (double& r : mesh.tet_fields.scalars["radius_edge_ratio"]) r = std::isfinite(r) ? r : 1e30;
  mesh.tet_fields.scalars["min_dihedral_deg"] = quality.min_dihedral_deg;
  std::printf("%s%s", report.summary().c_str(), quality.summary().c_str());
  if (!a.output.empty()) {
    Stopwatch write_watch;
    write_tet_mesh(a.output, mesh);
    std::printf("wrote %s (%s)\n", a.output.c_str(), format_seconds(write_watch.seconds()).c_str());
  }
  if (!a.render.empty()) {
    RenderSettings settings;
    settings.width = settings.height = 1024;
    write_png(a.render, render_view(cut_scene(mesh), settings, "three_quarter", ViewAxes{}));
    std::printf("picture: %s\n", a.render.c_str());
  }
  std::printf("done in %s\n", format_seconds(watch.seconds()).c_str());
  return 0;
}

const RegisterCommand tetrahedralize_command{
    "tetrahedralize", [](CLI::App& app) {
      auto* sub = app.add_subcommand(
          "tetrahedralize", "Labelled flesh/bone tet mesh of a body part from skin and bone surfaces, CT or a phantom");
      auto a = std::make_shared<TetArgs>();
      sub->add_option("--skin", a->skin, "Closed skin surface (any mesh format)");
      sub->add_option("--bone", a->bones, "Closed bone surface(s) inside the skin")->needs("--skin");
      sub->add_option("--unit", a->unit, "Unit of the surface files: auto, m, cm, mm or in");
      sub->add_option("--ct", a->ct, "CT volume (.nrrd, .nhdr, .mhd, .mha, DICOM folder) instead of surfaces")
          ->excludes("--skin");
      sub->add_option("--skin-iso", a->skin_iso, "Skin iso-value of the CT (HU+1024: 500)");
      sub->add_option("--bone-iso", a->bone_iso, "Bone iso-value of the CT (HU+1024: 1150)");
      sub->add_option("--phantom", a->phantom, "Built-in phantom when no surfaces or CT are given: arm or head");
      sub->add_option("--phantom-voxel", a->phantom_voxel_mm, "Voxel size of the phantom surfaces (mm)")
          ->check(CLI::Range(0.5, 10.0));
      sub->add_option("--edge", a->edge, "Target tet edge length (mm); default 8 unless --nodes or --paper")
          ->check(CLI::Range(0.05, 1000.0));
      sub->add_option("--nodes", a->nodes, "Target node count instead of an edge length")->excludes("--edge");
      sub->add_flag("--paper", a->paper, "Node count of the paper's Table 1 for the phantom (arm 29k, head 35k)");
      sub->add_option("--radius-edge", a->radius_edge, "Bound on circumradius / shortest edge")
          ->check(CLI::Range(1.0, 10.0));
      sub->add_option("--min-dihedral", a->min_dihedral, "Sliver exudation target angle (degrees)")
          ->check(CLI::Range(0.0, 30.0));
      sub->add_option("-o,--out", a->output, "Output tet mesh (.msh, .vtu, .node)");
      sub->add_option("--render", a->render, "Also write a PNG picture of a cut-away of the tets");
      return [a]() { return run_tetrahedralize(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
