// forensim demo: runs every system that exists on built-in defaults (and on the shared real data when it
// is present) and writes a self-contained HTML report with pictures, figures and timings.

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "body/phantom_model.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/data_dir.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "image/jpeg_io.hpp"
#include "image/png_io.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "mesh_processing/repair_mesh.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "phantoms/forearm_uv.hpp"
#include "phantoms/phantom_surface.hpp"
#include "phantoms/skin_maps.hpp"
#include "pictures.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "report/html_report.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"
#include "texture/normal_from_height.hpp"
#include "texture/uv_bake.hpp"
#include "texture/uv_seams.hpp"
#include "volume/iso_surface.hpp"
#include "volume/volume_reader.hpp"
#include "wound/abrasion.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim::cli {
namespace {

struct DemoArgs {
  std::string out = "out/demo";
  std::string data;
  int picture_size = 640;
  int samples = 8;
  std::string model_size = "paper";
  int uv_resolution = 2048;
};

struct DemoContext {
  RunFolder& run;
  HtmlReport& report;
  RenderSettings settings;
  std::vector<std::vector<std::string>> timing_rows;
  std::vector<std::vector<std::string>> model_rows;  // one per tetrahedralised body model

  // Writes a picture into the run folder and the report.
  void picture(const Image& image, const std::string& file, const std::string& caption) {
    const std::string bytes = encode_png(image);
    run.write(file, bytes);
    report.figure_png(bytes, caption);
  }
  void timed(const std::string& stage, double seconds) {
    run.timings().add(stage, seconds);
    timing_rows.push_back({stage, format_seconds(seconds)});
  }
};

std::filesystem::path data_folder(const DemoArgs& a) {
  if (!a.data.empty()) return a.data;
  return shared_data_dir();
}

std::vector<std::pair<std::string, std::string>> surface_facts(const std::string& label, const TriMesh& mesh) {
  return {
      {label + " triangles", format_count(mesh.triangle_count())},
      {label + " size", format_size_mm(bounding_box(mesh.positions).size())},
      {label + " topology", check_topology(mesh).summary()},
      {label + " enclosed volume", std::to_string(static_cast<long long>(enclosed_volume(mesh) / 1000.0)) + " cm^3"}};
}

// Skin and bone surfaces of a CT volume, with pictures: skin over skull, and a cut-away.
void ct_section(DemoContext& ctx, const ScalarGrid& grid, const std::string& name, const std::string& file_stem,
                const ViewAxes& axes, double skin_iso, double bone_iso) {
  Stopwatch watch;
  IsoSurfaceOptions options;
  options.keep_largest_components = 1;
  options.smoothing_iterations = 8;
  auto skin = std::make_shared<const TriMesh>(extract_iso_surface(grid, skin_iso, options));
  options.keep_largest_components = 0;
  auto bone = std::make_shared<const TriMesh>(extract_iso_surface(grid, bone_iso, options));
  ctx.timed(
      name + ": iso-surfaces (skin " + std::to_string(int(skin_iso)) + ", bone " + std::to_string(int(bone_iso)) + ")",
      watch.seconds());
  write_mesh(ctx.run.file(file_stem + "_skin.glb"), *skin);
  write_mesh(ctx.run.file(file_stem + "_bone.glb"), *bone);
  ctx.run.add_output(file_stem + "_skin.glb");
  ctx.run.add_output(file_stem + "_bone.glb");
  auto facts = surface_facts("skin", *skin);
  for (auto& f : surface_facts("bone", *bone)) facts.push_back(f);
  facts.insert(facts.begin(),
               {"volume", std::to_string(grid.nx) + " x " + std::to_string(grid.ny) + " x " + std::to_string(grid.nz) +
                              " samples, " + format_size_mm(grid.world_bounds().size())});
  ctx.report.facts(facts);
  ctx.run.facts()[file_stem] = {{"skin_triangles", skin->triangle_count()},
                                {"bone_triangles", bone->triangle_count()},
                                {"skin_closed", check_topology(*skin).is_closed()},
                                {"bone_closed", check_topology(*bone).is_closed()}};
  watch.restart();
  std::vector<SheetCell> cells;
  cells.push_back({render_view(skin_over_bone_scene(skin, bone, 0.3, axes), ctx.settings, "front", axes),
                   "skin (semi-transparent) over bone, front"});
  cells.push_back({render_view(skin_over_bone_scene(skin, bone, 0.3, axes), ctx.settings, "three_quarter", axes),
                   "three-quarter view"});
  // The cut removes the subject's left half; the camera looks at the cut from that side.
  cells.push_back(
      {render_view(cutaway_scene(skin, bone, axes.left(), axes), ctx.settings, "left", axes), "mid-sagittal cut-away"});
  ctx.picture(make_sheet(cells, 3, name), file_stem + "_surfaces.png", name + ": skin and bone surfaces");
  ctx.timed(name + ": pictures", watch.seconds());
}

void phantom_section(DemoContext& ctx, const std::string& name) {
  Stopwatch watch;
  const auto phantom = make_phantom(name);
  auto skin = std::make_shared<const TriMesh>(phantom_surface(*phantom, PhantomSurface::skin, 1.5, 4));
  auto bone = std::make_shared<const TriMesh>(phantom_surface(*phantom, PhantomSurface::bone, 1.5, 4));
  ctx.timed("phantom " + name + ": surfaces", watch.seconds());
  auto facts = surface_facts("skin", *skin);
  for (auto& f : surface_facts("bone", *bone)) facts.push_back(f);
  ctx.report.facts(facts);
  watch.restart();
  const auto cells = phantom_view_cells(name, skin, bone, ctx.settings);
  ctx.picture(make_sheet(cells, 4, "phantom: " + name), "phantom_" + name + ".png", "Built-in phantom '" + name + "'");
  ctx.timed("phantom " + name + ": pictures", watch.seconds());
}

std::string length_mm(double mm) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f mm", mm);
  return text;
}

std::string percent(double value, double reference) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f %%", 100.0 * (value / reference - 1.0));
  return text;
}

// The forearm-uv phantom: UV atlas figures, skin maps and textured pictures.
void forearm_uv_section(DemoContext& ctx, int resolution) {
  ForearmUvOptions options;
  options.resolution = resolution;
  const ForearmUvModel model = make_forearm_uv(options);
  ctx.timed("phantom forearm-uv: surface and UV atlas", model.seconds_surface + model.seconds_atlas);
  const SkinMaps maps = make_skin_maps(model.mesh, resolution, 1);
  ctx.timed("phantom forearm-uv: skin maps " + std::to_string(resolution) + "^2", maps.seconds);
  const ForearmUvStats& st = model.stats;
  char stretch[96], seams[96];
  std::snprintf(stretch, sizeof stretch, "%.3f (worst chart %.3f), area distortion %.3f", st.l2_stretch,
                st.max_chart_l2_stretch, st.area_distortion);
  std::snprintf(seams, sizeof seams, "%.0f mm, %.0f %% on hidden (palmar) sides", st.seam_length_mm,
                100.0 * st.hidden_seam_fraction);
  ctx.report.facts({{"skin", format_count(model.mesh.triangle_count()) + " triangles, " +
                                 std::to_string(model.chart_names.size()) + " UV charts"},
                    {"L2 stretch (1 = none)", stretch},
                    {"seams", seams},
                    {"overlaps", st.overlap_free ? "none" : "found"},
                    {"packing", std::to_string(static_cast<int>(100.0 * st.packing_efficiency + 0.5)) + " %"},
                    {"maps", std::to_string(resolution) + "^2: epidermis, dermis, specular, normal"}});
  ctx.run.facts()["forearm_uv"] = {{"overlap_free", st.overlap_free}, {"l2_stretch", st.l2_stretch}};
  Stopwatch watch;
  const auto cells =
      textured_arm_cells(std::make_shared<const TriMesh>(model.mesh), std::make_shared<const Image>(maps.epidermis),
                         std::make_shared<const Image>(maps.normal), ctx.settings);
  ctx.picture(make_sheet(cells, 3, "phantom: forearm-uv"), "phantom_forearm_uv.png",
              "forearm-uv: the skin with its procedural maps, and the colour map's UV layout");
  ctx.picture(make_sheet({{maps.dermis.resized(ctx.settings.width, ctx.settings.height), "lower skin (dermis)"},
                          {maps.specular.resized(ctx.settings.width, ctx.settings.height), "specular"},
                          {maps.normal.resized(ctx.settings.width, ctx.settings.height), "normal (tangent space)"}},
                         3, "forearm-uv: the other maps"),
              "phantom_forearm_uv_maps.png", "forearm-uv: lower skin colour, specular and normal maps");
  ctx.timed("phantom forearm-uv: pictures", watch.seconds());
}

// One row of the body-model table: counts, volume errors, quality and time.
// Value of a region map at a UV, or -1 outside the region.
float canvas_at_uv(const WoundCanvas& c, const Image& image, const Vec2& uv) {
  const Vec2 px = uv_to_pixel(uv, c.full_width, c.full_height);
  const int x = static_cast<int>(std::floor(px.x())) - c.region.x0;
  const int y = static_cast<int>(std::floor(px.y())) - c.region.y0;
  if (x < 0 || y < 0 || x >= c.width() || y >= c.height()) return -1.0f;
  return image.at(x, y);
}

std::string side_text(const WoundCanvas& c, const Vec2& uv) {
  if (canvas_at_uv(c, c.shape, uv) < 0.5f) return "outside the wound";
  char buf[64];
  std::snprintf(buf, sizeof buf, "inside, %.1f mm from its border", canvas_at_uv(c, c.inside_mm, uv));
  return buf;
}

// A wound painted across a UV seam of the Lee Perry-Smith head scan with its colour map as the upper skin:
// distances on the surface in 3D (continuous across the seam) beside the thesis's UV-space way (the wound
// stops at the seam), as the slow test tests/wound/slow_seam_head.cpp checks.
void wound_seam_section(DemoContext& ctx, const std::filesystem::path& folder) {
  Stopwatch watch;
  MeshImportOptions import_options;
  import_options.scale = 30.0;  // arbitrary units; about 30 mm each gives a 26 cm head and neck
  const TriMesh mesh = import_mesh(folder / "LeePerrySmith.glb", import_options);
  const int size = 1024;
  Image upper = read_image(folder / "Map-COL.jpg").resized(size, size).with_channels(4);
  upper.set_encoding(PixelEncoding::linear);
  Image lower = upper;  // dermis under the scanned skin: redder and darker (as forensim wound without one)
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Vec4f u = upper.rgba(x, y);
      lower.set_rgba(x, y, Vec4f(u.x() * 1.05f, u.y() * 0.7f, u.z() * 0.75f, 1.0f));
    }
  const UvRaster raster = rasterize_uv(mesh, size, size);
  ctx.timed("wound on the head scan: mesh, colour map and UV raster", watch.lap());
  // A seam edge whose texels on both sides show the edge itself (not an overlapping UV island).
  const auto seams = uv_seam_edges(mesh);
  auto shows = [&](const Vec2& uv, const Vec3& p) {
    const Vec2 px = uv_to_pixel(uv, size, size);
    const auto i = raster.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
    return i >= 0 && (raster.texels[static_cast<std::size_t>(i)].position - p).norm() < 1.0;
  };
  const UvSeamEdge* chosen = nullptr;
  for (std::size_t i = seams.size() / 2; i < seams.size() + seams.size() / 2 && !chosen; ++i) {
    const UvSeamEdge& e = seams[i % seams.size()];
    if (shows(e.uv_a, e.midpoint) && shows(e.uv_b, e.midpoint)) chosen = &e;
  }
  if (!chosen) throw Error("no UV seam of the head scan shows on both sides");
  const UvSeamEdge& seam = *chosen;
  WoundStroke dot;
  dot.points = {seam.midpoint};
  dot.radius_mm = 7.0;
  CanvasOptions options;
  options.reach_mm = AbrasionParams{}.reach_mm();
  options.seed = 3;
  const WoundCanvas surface = make_wound_canvas(mesh, raster, {dot}, upper, lower, options);
  options.distance = DistanceMode::uv;
  const WoundCanvas uv = make_wound_canvas(mesh, raster, {dot}, upper, lower, options);
  ctx.timed("wound on the head scan: canvases (surface and UV)", watch.lap());

  // Close-up camera along the outward normal at the seam.
  const std::vector<Vec3> normals = vertex_normals(mesh);
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if ((mesh.positions[i] - seam.midpoint).squaredNorm() < (mesh.positions[nearest] - seam.midpoint).squaredNorm())
      nearest = i;
  Vec3 centroid = Vec3::Zero();
  for (const auto& p : mesh.positions) centroid += p;
  centroid /= static_cast<double>(mesh.positions.size());
  Vec3 normal = normals[nearest].normalized();
  if (normal.dot(seam.midpoint - centroid) < 0.0) normal = -normal;
  const double view = 2.0 * (dot.radius_mm + 12.5) * 1.3;
  const Camera camera = Camera::look_at(seam.midpoint + normal * (view / (2.0 * std::tan(15.0 * M_PI / 180.0))),
                                        seam.midpoint, std::abs(normal.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitY());
  std::vector<SheetCell> cells;
  std::vector<SheetCell> maps;
  for (const char* phase : {"vasodilation", "scab"}) {
    for (const WoundCanvas* c : {&surface, &uv}) {
      const bool on_surface = c == &surface;
      TiledMapSet tiles;
      make_abrasion_key(phase)->render_into(*c, 0.0, tiles);
      MapSet full = skin_map_set(upper, AbrasionParams{}.skin_reflection);
      tiles.write_into(c->upper_skin, full, c->region.x0, c->region.y0);
      Scene scene;
      SurfaceMaterial material = SurfaceMaterial::skin();
      material.colour_source = ColourSource::texture;
      material.base_colour = Vec3f(1, 1, 1);
      material.base_texture = std::make_shared<Image>(full.color);
      material.normal_map = std::make_shared<Image>(normal_from_height(full.height_mm, c->texels_per_mm));
      scene.add(mesh, material, "head");
      scene.camera = camera;
      const std::string how = on_surface ? "distances on the surface" : "the thesis's UV space";
      cells.push_back({Renderer(scene).render(camera, ctx.settings), std::string(phase) + ", " + how});
      if (std::string(phase) == "vasodilation") {
        maps.push_back({full.color.resized(ctx.settings.width, ctx.settings.height), "colour map, " + how});
      }
    }
  }
  ctx.timed("wound on the head scan: key positions and pictures", watch.lap());
  char density[96];
  std::snprintf(density, sizeof density, "%d^2 (Map-COL.jpg as the upper skin), %.1f texels/mm", size,
                surface.texels_per_mm);
  ctx.report.facts({{"texture", density},
                    {"wound", "a 7 mm dot at the midpoint of a UV seam edge"},
                    {"seam, side A (surface)", side_text(surface, seam.uv_a)},
                    {"seam, side B (surface)", side_text(surface, seam.uv_b)},
                    {"seam, side A (UV space)", side_text(uv, seam.uv_a)},
                    {"seam, side B (UV space)", side_text(uv, seam.uv_b)},
                    {"wound texels", format_count(surface.wound_texels) + " on the surface, " +
                                         format_count(uv.wound_texels) + " in UV space"}});
  ctx.picture(make_sheet(cells, 2, "wound across a UV seam of the head scan"), "wound_seam_head.png",
              "The same wound painted across a UV seam: left with distances on the surface (continuous over the "
              "seam), right the thesis's way in UV space (cut off at the seam, its glow too)");
  ctx.picture(make_sheet(maps, 2, "the colour maps"), "wound_seam_head_maps.png",
              "Vasodilation colour maps: on the surface the wound is painted into both UV islands the seam "
              "separates; in UV space only into one");
}

void add_model_row(DemoContext& ctx, const std::string& name, const TetMesh& volume, std::size_t skin_triangles,
                   const TetrahedralizeReport& r, double seconds) {
  const TetQualityReport q = tet_quality(volume);
  char quality[64];
  std::snprintf(quality, sizeof quality, "%.1f / %.2f", q.dihedral_min, q.radius_edge_max);
  ctx.model_rows.push_back({name, format_count(volume.vertex_count()), format_count(volume.tet_count()),
                            format_count(r.bone_tet_count), skin_triangles ? format_count(skin_triangles) : "-",
                            percent(r.tet_volume_mm3, r.skin_volume_mm3),
                            r.bone_volume_mm3 > 0 ? percent(r.bone_tet_volume_mm3, r.bone_volume_mm3) : "-", quality,
                            format_seconds(seconds)});
}

// A phantom's body model at the demo's size: tets, skin and tracking, with the Table 1 comparison.
void phantom_model_section(DemoContext& ctx, const std::string& name, const std::string& size_name) {
  const PhantomModelSize size = phantom_model_size(name, size_name);
  PhantomModelReport r;
  Stopwatch watch;
  const BodyModel model = make_phantom_model(size, {}, &r);
  const double seconds = watch.seconds();
  ctx.timed("body model " + name + " (" + size_name + ")", seconds);
  add_model_row(ctx, name + " phantom (" + size_name + ")", model.volume, model.skin.triangle_count(), r.volume,
                seconds);
  ctx.report.facts(
      {{"volume", format_count(model.volume.vertex_count()) + " nodes, " + format_count(model.volume.tet_count()) +
                      " tets (paper: " + format_count(size.paper_nodes) + " nodes, " + format_count(size.paper_tets) +
                      " tets)"},
       {"skin", format_count(model.skin.triangle_count()) +
                    " triangles (paper: " + format_count(size.paper_skin_triangles) + ")"},
       {"tracking", format_count(r.tracking.count) + " connections, " +
                        std::to_string(static_cast<int>(100.0 * r.tracking.ray_fraction() + 0.5)) +
                        " % by ray along -n, mean distance " + length_mm(r.tracking.mean_distance)},
       {"time", "surfaces " + format_seconds(r.seconds_surfaces) + ", tets " + format_seconds(r.seconds_volume) +
                    ", skin " + format_seconds(r.seconds_skin) + ", tracking " + format_seconds(r.seconds_tracking)}});
  watch.restart();
  const auto skin = std::make_shared<const TriMesh>(model.skin);
  ctx.picture(make_sheet(tet_model_cells(body_views(name), skin, model.volume, ctx.settings), 3,
                         name + " body model (" + size_name + ")"),
              "model_" + name + ".png", name + ": skin, and the tets cut open (flesh red, bone pale)");
  ctx.timed("body model " + name + ": pictures", watch.seconds());
}

// A real input tetrahedralised: a scan (skin only) or a CT (skin and skull).
void real_model_section(DemoContext& ctx, const std::string& name, const TriMesh& skin,
                        const std::vector<TriMesh>& bones, const TetrahedralizeOptions& options, const ViewAxes& axes,
                        const std::string& file_stem) {
  TetrahedralizeReport r;
  Stopwatch watch;
  const TetMesh volume = tetrahedralize(skin, bones, options, &r);
  const double seconds = watch.seconds();
  ctx.timed(name + ": tetrahedralize", seconds);
  add_model_row(ctx, name, volume, 0, r, seconds);
  std::vector<std::pair<std::string, std::string>> facts{
      {"tets", format_count(volume.vertex_count()) + " nodes, " + format_count(volume.tet_count()) + " tets (" +
                   format_count(r.bone_tet_count) + " bone)"},
      {"volume", "tets " + percent(r.tet_volume_mm3, r.skin_volume_mm3) + " of the skin surface's" +
                     (r.bone_volume_mm3 > 0 ? ", bone tets " + percent(r.bone_tet_volume_mm3, r.bone_volume_mm3) +
                                                  " of the bone surfaces'"
                                            : std::string())}};
  for (const std::string& note : r.notes) facts.emplace_back("input", note);
  ctx.report.facts(facts);
  watch.restart();
  const auto shown = std::make_shared<const TriMesh>(skin);
  ctx.picture(make_sheet(tet_model_cells(body_views("head", axes), shown, volume, ctx.settings), 3, name),
              file_stem + ".png", name + ": surface, and the tets cut open");
  ctx.timed(name + ": pictures", watch.seconds());
}

// `mm_per_unit` scales files in arbitrary units (0 = the file's own unit).
void scan_section(DemoContext& ctx, const std::filesystem::path& path, const std::string& name, const ViewAxes& axes,
                  const std::string& view, double mm_per_unit) {
  Stopwatch watch;
  TriMesh mesh = import_mesh(path, {"auto", mm_per_unit});
  const TopologyReport before = check_topology(mesh);
  RepairOptions options;
  options.max_hole_edges = 200;
  const RepairReport report = repair_mesh(mesh, options);
  ctx.timed(name + ": import and repair", watch.seconds());
  ctx.report.facts(
      {{"file", path.filename().string()},
       {"triangles", format_count(mesh.triangle_count())},
       {"size", format_size_mm(bounding_box(mesh.positions).size())},
       {"as read", before.summary()},
       {"after repair", report.after.summary()},
       {"holes filled", std::to_string(report.holes_filled) + " of " + std::to_string(report.holes_found)}});
  watch.restart();
  Scene scene;
  auto shared = std::make_shared<const TriMesh>(std::move(mesh));
  scene.add(shared, SurfaceMaterial::clay(), name);
  ctx.picture(render_view(scene, ctx.settings, view, axes), "scan_" + path.stem().string() + ".png",
              name + " (" + path.filename().string() + "), repaired");
  ctx.timed(name + ": picture", watch.seconds());
}

using Stages = std::vector<std::pair<std::string, std::function<void()>>>;

// Out of line: GCC 12 reports false array-bounds and null-dereference warnings when the std::function
// construction of these large lambdas is inlined into run_demo.
[[gnu::noinline]] void add_stage(Stages& stages, const std::string& label, std::function<void()> stage) {
  stages.emplace_back(label, std::move(stage));
}

int run_demo(const DemoArgs& a) {
  Stopwatch total;
  RunFolder run(a.out, "demo");
  HtmlReport report("forensim demo report");
  DemoContext ctx{run, report, {}, {}, {}};
  ctx.settings.width = ctx.settings.height = a.picture_size;
  ctx.settings.samples_per_pixel = a.samples;
  const std::filesystem::path data = data_folder(a);
  const bool have_data = std::filesystem::exists(data / "ct-head-headsq" / "quarter.nhdr");
  run.set_job({{"out", a.out},
               {"data", have_data ? data.string() : ""},
               {"picture_size", a.picture_size},
               {"samples", a.samples}});
  run.set_seed(ctx.settings.seed);

  report.paragraph(
      "forensim simulates how a human body's appearance changes after injury and after death, and "
      "rebuilds a face from a skull. This report is written by `forensim demo`: every system that exists "
      "so far, run on the built-in procedural phantoms" +
      std::string(have_data ? " and on the real data in " + data.string() : "") + ".");
  if (!have_data) {
    report.warning("Shared real data not found at " + data.string() +
                   "; the sections on real CT and scans are skipped (set FORENSIM_DATA_DIR or --data).");
  }

  Stages stages;
  add_stage(stages, "CT head phantom", [&] {
    report.section(
        "Foundation: CT volume to skin and bone surfaces (built-in phantom)",
        "The procedural CT of the head phantom (HU+1024 values, 2 mm voxels), iso-surfaced at 500 (skin) and "
        "1150 (bone) into closed, oriented meshes.");
    Stopwatch w;
    const ScalarGrid grid = make_ct_head_phantom({2.0, 20.0, 1});
    ctx.timed("CT phantom: sampling", w.seconds());
    ct_section(ctx, grid, "CT head phantom", "ct_phantom", ViewAxes{}, ct_phantom_skin_iso, ct_phantom_bone_iso);
  });
  if (have_data) {
    add_stage(stages, "real CT", [&] {
      report.section(
          "Foundation: real CT to skin and bone surfaces",
          "VTK's headsq CT (Kitware, via pyvista/vtk-data; 64 x 64 x 93 at 3.2 x 3.2 x 1.5 mm), read from its "
          "detached NRRD header with 93 slice files, iso-surfaced at 500 (skin) and 1150 (bone) as in VTK's "
          "medical examples. Slice 1 is superior, so the scan's z axis points down.");
      Stopwatch w;
      const ScalarGrid grid = read_volume(data / "ct-head-headsq" / "quarter.nhdr");
      ctx.timed("real CT: reading", w.seconds());
      ct_section(ctx, grid, "CT head (headsq)", "ct_headsq", ViewAxes{-Vec3::UnitZ(), -Vec3::UnitY()}, 500.0, 1150.0);
    });
  }
  for (const std::string name : {"arm", "head"}) {
    add_stage(stages, "phantom " + name, [&ctx, &report, name] {
      report.section("Body-part phantom: " + name,
                     name == "arm"
                         ? "Right forearm and hand with radius, ulna, carpals, metacarpals and phalanges "
                           "(signed distance functions in mm, surfaces at 1.5 mm sampling)."
                         : "Head and neck with brow, closed eyelids, nose, lips, chin, cheeks and ears over a "
                           "skull with orbits, nasal aperture, zygomatic arches, maxilla, teeth, mandible and "
                           "cervical spine.");
      phantom_section(ctx, name);
    });
  }
  add_stage(stages, "phantom forearm-uv", [&] {
    report.section("Body-part phantom: forearm-uv",
                   "The arm's skin as a painting surface for the wound system: a UV atlas (charts cut along the "
                   "palmar sides, flattened with ARAP or LSCM, packed at one texel density) and procedural skin "
                   "maps baked from solid noise at the 3D surface points, so they match across seams.");
    forearm_uv_section(ctx, a.uv_resolution);
  });
  const std::filesystem::path head_scan = data / "head-scan-lee-perry-smith";
  add_stage(stages, "wound across a UV seam", [&] {
    report.section("Wound healing: a wound across a UV seam of a scanned head",
                   "An abrasion (Linnenbank 2015, chapter 4) painted on the Lee Perry-Smith head scan (CC BY 3.0) "
                   "across a UV seam, with the scan's colour map as the upper skin. forensim measures distances "
                   "on the surface in 3D from baked per-texel surface positions, so the wound continues across "
                   "the seam; the thesis's way measures them in UV space, where the wound stops at the seam.");
    if (!std::filesystem::exists(head_scan / "LeePerrySmith.glb") ||
        !std::filesystem::exists(head_scan / "Map-COL.jpg")) {
      report.warning(
          "Skipped: the head scan (head-scan-lee-perry-smith/LeePerrySmith.glb and Map-COL.jpg) is "
          "not in " +
          data.string() + " (set FORENSIM_DATA_DIR or --data).");
      return;
    }
    wound_seam_section(ctx, head_scan);
  });
  for (const std::string name : {"arm", "head"}) {
    add_stage(stages, "body model " + name, [&ctx, &report, &a, name] {
      report.section(
          "Body model: " + name + " (" + a.model_size + " size)",
          "The desiccation system's object representation (Frerichs et al. 2020, section 4 and Table 1): a tet "
          "volume labelled flesh or bone (CGAL Mesh_3 on the phantom's skin and bone surfaces), a separate "
          "isotropically remeshed skin, and a tracking connection from every skin vertex to the volume's boundary "
          "(section 8.2).");
      phantom_model_section(ctx, name, a.model_size);
    });
  }
  if (have_data) {
    add_stage(stages, "real body models", [&] {
      report.section("Body models from real inputs",
                     "A scan (the hand, closed, scaled to 190 mm) and a CT (headsq: skin at 500, skull at 1150 "
                     "as the bone region) tetrahedralised with the same mesher.");
      if (std::filesystem::exists(data / "hand-mesh" / "hand_closed.obj")) {
        TetrahedralizeOptions options;
        options.edge_length_mm = 11.0;  // about 8000 nodes
        real_model_section(ctx, "hand scan", import_mesh(data / "hand-mesh" / "hand_closed.obj", {"auto", 200.0}), {},
                           options, ViewAxes{Vec3::UnitY(), Vec3::UnitZ()}, "model_hand_scan");
      }
      const ScalarGrid grid = read_volume(data / "ct-head-headsq" / "quarter.nhdr");
      const TriMesh skin = ct_body_surfaces(grid, 500.0, 1150.0).skin;
      TetrahedralizeOptions options;
      options.target_nodes = 20000;
      TetrahedralizeReport r;
      Stopwatch watch;
      const TetMesh volume = tetrahedralize_ct(grid, 500.0, 1150.0, options, &r);
      const double seconds = watch.seconds();
      ctx.timed("CT head (headsq): tetrahedralize", seconds);
      add_model_row(ctx, "CT head (headsq)", volume, 0, r, seconds);
      report.facts({{"tets", format_count(volume.vertex_count()) + " nodes, " + format_count(volume.tet_count()) +
                                 " tets (" + format_count(r.bone_tet_count) + " bone)"},
                    {"volume", "tets " + percent(r.tet_volume_mm3, r.skin_volume_mm3) + " of the skin's, bone tets " +
                                   percent(r.bone_tet_volume_mm3, r.bone_volume_mm3) + " of the skull's"}});
      const ViewAxes axes{-Vec3::UnitZ(), -Vec3::UnitY()};
      ctx.picture(make_sheet(tet_model_cells(body_views("head", axes), std::make_shared<const TriMesh>(skin), volume,
                                             ctx.settings),
                             3, "CT head (headsq)"),
                  "model_ct_headsq.png", "CT head: skin, and the tets cut open with the skull as bone");
    });
  }
  add_stage(stages, "body model table", [&] {
    report.section(
        "Body models: sizes, accuracy, quality and time",
        "Volume error: tet volume against the volume enclosed by the input surface (and bone tets against "
        "the bone surfaces). Quality: smallest dihedral angle (degrees) / largest radius-edge ratio. Table 1 "
        "of the paper: arm 29k nodes, 141k tets, 19k skin triangles; head 35k nodes, 149k tets, 122k skin "
        "triangles.");
    report.table({"model", "nodes", "tets", "bone tets", "skin triangles", "volume error", "bone volume error",
                  "quality", "time"},
                 ctx.model_rows);
  });
  if (have_data && std::filesystem::exists(data / "hand-mesh" / "hand_closed.obj")) {
    add_stage(stages, "scans", [&] {
      report.section("Real scans: import and repair",
                     "Scanned meshes imported through Assimp in millimetres, then repaired (duplicates, degenerate "
                     "triangles, orientation, holes) on CGAL.");
      // Arbitrary units, 0.94 units tall (its SOURCE.md): scaled to a 190 mm hand.
      scan_section(ctx, data / "hand-mesh" / "hand_closed.obj", "Hand scan", ViewAxes{Vec3::UnitY(), Vec3::UnitZ()},
                   "front", 200.0);
      if (std::filesystem::exists(data / "head-busts" / "nefertiti-lowres.obj")) {
        scan_section(ctx, data / "head-busts" / "nefertiti-lowres.obj", "Nefertiti bust",
                     ViewAxes{Vec3::UnitY(), Vec3::UnitZ()}, "three_quarter", 0.0);
      }
    });
  }

  Progress progress("demo", stages.size());
  for (auto& [label, stage] : stages) {
    if (interrupt_requested()) throw CancelledError("demo interrupted before '" + label + "'");
    try {
      stage();
    } catch (const Error& e) {
      // One failing stage is reported on the page; the rest of the demo still runs.
      spdlog::error("demo stage '{}' failed: {}", label, e.what());
      report.warning("Stage '" + label + "' failed: " + e.what());
    }
    progress.advance();
  }
  progress.finish();

  report.section("Timings", "Wall-clock seconds on this machine (" + std::to_string(thread_count()) + " threads).");
  ctx.timing_rows.push_back({"total", format_seconds(total.seconds())});
  report.table({"stage", "time"}, ctx.timing_rows);
  report.section("How to cite");
  report.paragraph(
      "Desiccation: Frerichs, Vidler, Gatzidis, Computer graphics simulation of natural mummification by "
      "desiccation, Computer Animation and Virtual Worlds 31:e1927, 2020. Wound healing: Linnenbank, "
      "Real-time simulation of abrasion wound healing, MSc thesis, Utrecht University, 2015. Craniofacial "
      "reconstruction: Kaehler, Haber, Seidel, Reanimating the dead: reconstruction of expressive faces "
      "from skull data, ACM TOG 22(3), 2003.");
  report.write(run.file("report.html"));
  run.add_output("report.html");
  run.timings().add("total", total.seconds());
  run.write_record();
  std::printf("forensim demo: report at %s (%s)\n", (run.path() / "report.html").string().c_str(),
              format_seconds(total.seconds()).c_str());
  return 0;
}

const RegisterCommand demo_command{
    "demo", [](CLI::App& app) {
      auto* sub = app.add_subcommand("demo",
                                     "Run every system on built-in defaults (and shared data if present); write an "
                                     "HTML report with pictures and timings");
      auto a = std::make_shared<DemoArgs>();
      sub->add_option("-o,--out", a->out, "Output folder (report.html, pictures, meshes, run.json)");
      sub->add_option("--data", a->data, "Folder of shared real data (default: $FORENSIM_DATA_DIR or ../shared/data)");
      sub->add_option("--picture-size", a->picture_size, "Pixels per picture side")->check(CLI::Range(64, 4096));
      sub->add_option("--samples", a->samples, "Samples per pixel")->check(CLI::Range(1, 256));
      sub->add_option("--model-size", a->model_size, "Size of the phantom body models: small, paper or fine");
      sub->add_option("--uv-resolution", a->uv_resolution, "Size of the forearm-uv skin maps")
          ->check(CLI::Range(64, 8192));
      return [a]() { return run_demo(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
