// forensim tetrahedralize: a labelled (flesh/bone), surface-conforming tet mesh of a body part from skin and
// bone surfaces, a CT volume or a built-in phantom; optionally the whole body model (volume, skin, tracking
// connections) as a folder, and pictures.

#include <cmath>
#include <cstdio>

#include "body/body_model_io.hpp"
#include "body/phantom_model.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "pictures.hpp"
#include "render/sheet.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

struct TetArgs {
  std::string skin, unit = "auto", ct, phantom = "arm", size, output, model, render, axes = "lps";
  std::vector<std::string> bones;
  std::vector<double> up, front, gravity;  ///< --up, --front, --gravity (empty: from --axes and the input)
  double bone_offset = 0.0;
  double time_limit = 0.0;
  double scale = 0.0;
  double skin_iso = 500.0, bone_iso = 1150.0;
  double edge = 0.0;
  std::size_t nodes = 0, tets = 0, skin_triangles = 0;
  double interior = 1.0;
  double surface_distance = 0.01;
  double radius_edge = 2.0;
  double min_dihedral = 12.0;
  double phantom_voxel_mm = 2.0;
  unsigned seed = 0;
  int picture_size = 640;
  bool close_openings = false;
  bool non_manifold = false;
  bool no_perturb = false;
};

/// The skin of a model from real input: as given, or remeshed isotropically to about `triangles`.
TriMesh model_skin(const TriMesh& skin, std::size_t triangles) {
  return triangles == 0 ? skin : remesh_to_triangle_count(skin, triangles);
}

Vec3 unit_vector(const std::vector<double>& v, const char* option) {
  const Vec3 x(v[0], v[1], v[2]);
  if (!x.allFinite() || x.norm() < 1e-9)
    throw Error(std::string(option) + " must be a finite, non-zero vector", ErrorKind::usage);
  return x.normalized();
}

/// The pose of a model from a scan or CT: its axes from --up/--front or --axes; gravity from --gravity, else
/// towards the back for a CT (scanned lying on its back), else down.
BodyPose input_pose(const TetArgs& a) {
  BodyPose pose;
  pose.views = "head";
  const ViewAxes axes = axes_from_name(a.axes);
  pose.up = axes.up;
  pose.front = axes.front;
  if (!a.up.empty() || !a.front.empty()) {
    if (a.up.empty() || a.front.empty()) throw Error("--up and --front go together", ErrorKind::usage);
    pose.up = unit_vector(a.up, "--up");
    pose.front = unit_vector(a.front, "--front");
    if (std::abs(pose.up.dot(pose.front)) > 1e-3) throw Error("--up and --front must be orthogonal", ErrorKind::usage);
    pose.front = (pose.front - pose.front.dot(pose.up) * pose.up).normalized();
  }
  pose.gravity = !a.gravity.empty() ? unit_vector(a.gravity, "--gravity") : a.ct.empty() ? -pose.up : -pose.front;
  return pose;
}

int run_tetrahedralize(const TetArgs& a) {
  Stopwatch watch;
  TetrahedralizeOptions options;
  options.edge_length_mm = a.edge;
  options.target_nodes = a.nodes;
  options.target_tets = a.tets;
  options.interior_size_factor = a.interior;
  options.surface_distance_fraction = a.surface_distance;
  options.radius_edge_bound = a.radius_edge;
  options.min_dihedral_deg = a.min_dihedral;
  options.seed = a.seed;
  options.close_openings = a.close_openings;
  options.bone_offset_mm = a.bone_offset;
  options.manifold_boundary = !a.non_manifold;
  if (a.no_perturb) options.perturb = false;
  options.time_limit_s = a.time_limit;
  const bool phantom_input = a.skin.empty() && a.ct.empty();
  if (!a.size.empty() && !phantom_input) throw Error("--size applies to the built-in phantoms only", ErrorKind::usage);
  if (!a.size.empty() && (a.edge > 0 || a.nodes > 0 || a.tets > 0))
    throw Error("--size sets the mesh size; leave out --edge, --nodes and --tets", ErrorKind::usage);
  if (phantom_input && (!a.up.empty() || !a.front.empty() || !a.gravity.empty() || a.bone_offset > 0.0))
    throw Error("--up, --front, --gravity and --bone-offset apply to scans and CTs; phantoms have their own",
                ErrorKind::usage);
  if (a.skin_triangles > 0 && phantom_input && !a.size.empty())
    throw Error("--size sets the skin size of a phantom; leave out --skin-triangles", ErrorKind::usage);

  if (!a.output.empty()) check_output_path(a.output, OutputKind::file);
  if (!a.model.empty()) check_output_path(a.model, OutputKind::folder);
  if (!a.render.empty()) check_output_path(a.render, OutputKind::file);

  TetrahedralizeReport report;
  TetMesh mesh;
  TriMesh skin;  // the skin of the model (a separate surface over the volume)
  BodyModel model;
  bool have_model = false;
  BodyViews views = body_views(a.phantom);
  const BodyPose pose = phantom_input ? BodyPose::of_phantom(a.phantom) : input_pose(a);
  if (!a.size.empty()) {
    const PhantomModelSize size = phantom_model_size(a.phantom, a.size);
    std::printf("input: %s phantom, size '%s' (%zu volume nodes, %zu skin triangles)\n", a.phantom.c_str(),
                a.size.c_str(), size.volume_nodes, size.skin_triangles);
    PhantomModelReport model_report;
    model = make_phantom_model(size, options, &model_report);
    have_model = true;
    report = model_report.volume;
    std::printf("%s", model_report.summary().c_str());
    if (size.paper_nodes > 0) {
      std::printf("paper (Table 1): %zu nodes, %zu tets, %zu skin triangles; here %+.1f %%, %+.1f %%, %+.1f %%\n",
                  size.paper_nodes, size.paper_tets, size.paper_skin_triangles,
                  100.0 * (static_cast<double>(model.volume.vertex_count()) / size.paper_nodes - 1.0),
                  100.0 * (static_cast<double>(model.volume.tet_count()) / size.paper_tets - 1.0),
                  100.0 * (static_cast<double>(model.skin.triangle_count()) / size.paper_skin_triangles - 1.0));
    }
    mesh = model.volume;
    skin = model.skin;
  } else {
    if (options.edge_length_mm <= 0.0 && options.target_nodes == 0 && options.target_tets == 0) {
      if (!phantom_input) throw Error("give --edge, --nodes or --tets", ErrorKind::usage);
      options.edge_length_mm = 8.0;
    }
    if (!a.ct.empty()) {
      const ScalarGrid grid = read_volume(a.ct);
      std::printf("input: CT %s (%d x %d x %d), skin iso %g, bone iso %g\n", a.ct.c_str(), grid.nx, grid.ny, grid.nz,
                  a.skin_iso, a.bone_iso);
      mesh = tetrahedralize_ct(grid, a.skin_iso, a.bone_iso, options, &report);
      if (!a.model.empty() || !a.render.empty()) {
        skin = model_skin(ct_body_surfaces(grid, a.skin_iso, a.bone_iso).skin, a.skin_triangles);
      }
      views = body_views("head", ViewAxes{pose.up, pose.front});
    } else if (!a.skin.empty()) {
      const TriMesh input = import_mesh(a.skin, {a.unit, a.scale});
      std::vector<TriMesh> bones;
      for (const std::string& bone : a.bones) bones.push_back(import_mesh(bone, {a.unit, a.scale}));
      std::printf("input: skin %s (%zu triangles), %zu bone surface(s)\n", a.skin.c_str(), input.triangle_count(),
                  bones.size());
      mesh = tetrahedralize(input, bones, options, &report);
      if (!a.model.empty() || !a.render.empty()) {
        // With --close-openings the model's skin is the surface closed as the volume was, so it covers it all
        // (otherwise the input as given, keeping its UVs).
        std::vector<std::string> notes;
        skin = model_skin(a.close_openings ? closed_body_surface(input, "skin surface", true, notes) : input,
                          a.skin_triangles);
      }
      views = body_views("head", ViewAxes{pose.up, pose.front});
    } else {
      const auto phantom = make_phantom(a.phantom);
      const TriMesh phantom_skin = phantom_surface(*phantom, PhantomSurface::skin, a.phantom_voxel_mm);
      std::vector<TriMesh> bones{phantom_surface(*phantom, PhantomSurface::bone, 0.75 * a.phantom_voxel_mm)};
      std::printf("input: %s phantom (surfaces at %.2f mm voxels)\n", a.phantom.c_str(), a.phantom_voxel_mm);
      mesh = tetrahedralize(phantom_skin, bones, options, &report);
      skin = model_skin(phantom_skin, a.skin_triangles);
    }
    std::printf("%s", report.summary().c_str());
    if (!a.model.empty()) {
      Stopwatch tracking_watch;
      model = make_body_model(mesh, skin);
      model.pose = pose;
      have_model = true;
      const TrackingStats stats = tracking_stats(model.tracking);
      std::printf("tracking: %zu skin vertices, %.1f %% by ray, distance mean %.2f max %.2f mm (%s)\n", stats.count,
                  100.0 * stats.ray_fraction(), stats.mean_distance, stats.max_distance,
                  format_seconds(tracking_watch.seconds()).c_str());
    }
  }

  const TetQualityReport quality = tet_quality(mesh);
  std::printf("%s", quality.summary().c_str());
  if (!a.output.empty()) {
    TetMesh out = mesh;  // labels travel as the writers' region array; quality goes beside them
    out.tet_fields.scalars["radius_edge_ratio"] = quality.radius_edge_ratio;
    for (double& r : out.tet_fields.scalars["radius_edge_ratio"]) r = std::isfinite(r) ? r : 1e30;
    out.tet_fields.scalars["min_dihedral_deg"] = quality.min_dihedral_deg;
    Stopwatch write_watch;
    write_tet_mesh(a.output, out);
    std::printf("wrote %s (%s)\n", a.output.c_str(), format_seconds(write_watch.seconds()).c_str());
  }
  if (!a.model.empty() && have_model) {
    write_body_model(a.model, model);
    std::printf("wrote body model %s (model.json, volume.vtu, skin.vtu)\n", a.model.c_str());
  }
  if (!a.render.empty()) {
    RenderSettings settings;
    settings.width = settings.height = a.picture_size;
    auto shown = std::make_shared<const TriMesh>(skin);
    char title[160];
    std::snprintf(title, sizeof title, "%zu nodes, %zu tets (%zu bone), skin %zu triangles", mesh.vertex_count(),
                  mesh.tet_count(), report.bone_tet_count, skin.triangle_count());
    write_png(a.render, make_sheet(tet_model_cells(views, shown, mesh, settings), 3, title, SheetStyle{}));
    std::printf("picture: %s\n", a.render.c_str());
  }
  std::printf("done in %s\n", format_seconds(watch.seconds()).c_str());
  return 0;
}

const RegisterCommand tetrahedralize_command{
    "tetrahedralize", [](CLI::App& app) {
      auto* sub = app.add_subcommand(
          "tetrahedralize",
          "Labelled flesh/bone tet mesh (and body model) of a body part from skin and bone surfaces, CT or a phantom");
      auto a = std::make_shared<TetArgs>();
      sub->add_option("--skin", a->skin, "Closed skin surface (any mesh format)");
      sub->add_option("--bone", a->bones, "Closed bone surface(s) inside the skin")->needs("--skin");
      sub->add_option("--unit", a->unit, "Unit of the surface files: auto, m, cm, mm or in");
      sub->add_option("--scale", a->scale, "Millimetres per file unit (overrides --unit)")->check(CLI::PositiveNumber);
      sub->add_option("--ct", a->ct, "CT volume (.nrrd, .nhdr, .mhd, .mha, DICOM folder) instead of surfaces")
          ->excludes("--skin");
      sub->add_option("--skin-iso", a->skin_iso, "Skin iso-value of the CT (HU+1024: 500)");
      sub->add_option("--bone-iso", a->bone_iso, "Bone iso-value of the CT (HU+1024: 1150)");
      sub->add_option("--phantom", a->phantom, "Built-in phantom when no surfaces or CT are given: arm or head");
      sub->add_option("--size", a->size, "Phantom model size: small, paper (Table 1 of the paper) or fine");
      sub->add_option("--phantom-voxel", a->phantom_voxel_mm, "Voxel size of the phantom surfaces (mm)")
          ->check(CLI::Range(0.5, 10.0));
      sub->add_option("--edge", a->edge, "Target tet edge length (mm); default 8 for phantoms")
          ->check(CLI::Range(0.05, 1000.0));
      sub->add_option("--nodes", a->nodes, "Target node count instead of an edge length")->excludes("--edge");
      sub->add_option("--tets", a->tets, "Target tet count instead of an edge length")
          ->excludes("--edge")
          ->excludes("--nodes");
      sub->add_option("--interior-factor", a->interior, "Interior tets up to this many times the edge length")
          ->check(CLI::Range(0.25, 16.0));
      sub->add_option("--surface-distance", a->surface_distance,
                      "Largest distance of the boundary from the input surfaces, as a fraction of the edge length")
          ->check(CLI::Range(0.0005, 1.0));
      sub->add_option("--radius-edge", a->radius_edge, "Bound on circumradius / shortest edge")
          ->check(CLI::Range(1.0, 10.0));
      sub->add_option("--min-dihedral", a->min_dihedral, "Sliver exudation target angle (degrees)")
          ->check(CLI::Range(0.0, 30.0));
      sub->add_flag("--close-openings", a->close_openings,
                    "Cap large openings of the surfaces too (a bust's base, a cut limb), not only scan holes");
      sub->add_flag("--non-manifold", a->non_manifold, "Do not force a 2-manifold boundary (thin, touching shells)");
      sub->add_flag("--no-perturb", a->no_perturb,
                    "Skip Mesh_3's sliver perturbation (faster; exudation still removes slivers)");
      sub->add_option("--seed", a->seed, "Seed of the mesher's random choices");
      sub->add_option("--time-limit", a->time_limit,
                      "Stop a meshing pass that has not finished after this many seconds, with an error (default: "
                      "300 s plus 1 s per 2000 expected nodes)")
          ->check(CLI::Range(1.0, 1e6));
      sub->add_option("--skin-triangles", a->skin_triangles,
                      "Remesh the model's skin to about this many triangles (default: the input skin as is)");
      sub->add_option("-o,--out", a->output, "Output tet mesh (.msh, .vtu, .node) with quality per tet");
      sub->add_option("--model", a->model, "Write the body model (volume, skin, tracking) into this folder");
      sub->add_option("--axes", a->axes, "Axes of surface/CT input for pictures: lps (z up) or yup");
      sub->add_option("--up", a->up, "The subject's up x y z in the input's frame (with --front; overrides --axes)")
          ->expected(3);
      sub->add_option("--front", a->front, "The subject's front x y z in the input's frame (with --up)")->expected(3);
      sub->add_option("--gravity", a->gravity,
                      "Direction of gravity x y z as the body lay, stored in the model for livor mortis (default: "
                      "towards the back for a CT, which is scanned lying on its back; down for a surface)")
          ->expected(3);
      sub->add_option("--bone-offset", a->bone_offset,
                      "With a skin and no bones: use the skin's inner offset surface this deep (mm) as the bone, a "
                      "stand-in skeleton for scans")
          ->check(CLI::Range(0.5, 200.0))
          ->excludes("--bone")
          ->excludes("--ct");
      sub->add_option("--render", a->render, "Also write a PNG sheet: the skin from two sides and the tets cut open");
      sub->add_option("--picture-size", a->picture_size, "Pixels per picture side")->check(CLI::Range(32, 4096));
      return [a]() { return run_tetrahedralize(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
