// forensim wound: paints a wound on a skin mesh with UVs and writes its healing timeline (Linnenbank 2015's
// abrasion, or a bruise): the maps of every key position and of requested times, GLBs with the maps as PBR
// material, close-up renders of the phases on the displaced mesh, and a JSON description of the timeline.
// Everything is checked before the output folder is created, so bad input writes nothing.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/error.hpp"
#include "core/job.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "image/png_io.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/mesh_import.hpp"
#include "phantoms/forearm_uv.hpp"
#include "pictures.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "texture/normal_from_height.hpp"
#include "texture/uv_bake.hpp"
#include "wound/bruise.hpp"
#include "wound/duration.hpp"
#include "wound/timeline.hpp"
#include "wound/uv_cylinder.hpp"
#include "wound/wound_job.hpp"

namespace forensim::cli {
namespace {

struct WoundArgs {
  std::string mesh;
  std::string builtin = "forearm-uv";
  std::string strokes;
  std::string type;
  std::string distance;
  std::string shape;
  std::string upper_skin, lower_skin;
  std::string times = "1h,36h,5d,3w";
  int resolution = 1024;
  int picture_size = 320;
  int samples = 4;
  double texels_per_mm = 0.0;
  double mesh_scale = 0.0;
  std::string unit = "auto";
  std::uint64_t seed = 1;
  std::string out;
};

// A default stroke: a bent line about 30 mm long, through the mesh's middle along its longest axis, on the
// side facing the largest coordinate of the next axis (dorsal on the forearm; across the seam on the cylinder).
std::string default_strokes_json(const TriMesh& mesh) {
  Vec3 lo = mesh.positions[0], hi = lo;
  for (const auto& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 size = hi - lo;
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (size[k] > size[a]) a = k;
  int b = (a + 1) % 3;
  if (a == 0) b = 2;  // forearm: x along the arm, z dorsal
  const Vec3 centre = 0.5 * (lo + hi);
  auto nearest = [&](const Vec3& q) {
    std::size_t best = 0;
    double bd = 1e300;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const double d = (mesh.positions[i] - q).squaredNorm();
      if (d < bd) bd = d, best = i;
    }
    return mesh.positions[best];
  };
  Vec3 top = centre;
  top[b] = hi[b];
  const int c = 3 - a - b;
  nlohmann::json pts = nlohmann::json::array();
  for (int k = -1; k <= 1; ++k) {
    Vec3 q = top;
    q[a] += 12.0 * k;
    q[c] += (k == 0 ? 4.0 : -2.0);
    const Vec3 p = nearest(q);
    pts.push_back({p.x(), p.y(), p.z()});
  }
  nlohmann::json j;
  j["strokes"] = nlohmann::json::array({{{"points", pts}, {"radius_mm", 5.0}}});
  return j.dump();
}

// The mesh displaced along its vertex normals by the height map (mm), sampled at each vertex's first UV.
TriMesh displaced(const TriMesh& mesh, const Image& height_mm) {
  TriMesh out = mesh;
  if (out.normals.size() != out.positions.size()) out.normals = vertex_normals(out);
  std::vector<int> uv_of(out.positions.size(), -1);
  for (std::size_t f = 0; f < out.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (uv_of[static_cast<std::size_t>(out.triangles[f][k])] < 0) {
        uv_of[static_cast<std::size_t>(out.triangles[f][k])] = out.triangle_uvs[f][k];
      }
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    if (uv_of[v] < 0) continue;
    const double h = height_mm.sample_uv(out.uvs[static_cast<std::size_t>(uv_of[v])], WrapMode::clamp).x();
    out.positions[v] += out.normals[v] * h;
  }
  out.normals = vertex_normals(out);
  return out;
}

Image metallic_roughness(const Image& reflection) {
  const Image r = roughness_from_reflection(reflection);
  Image out(r.width(), r.height(), 3, 0.0f, PixelEncoding::data);
  for (int y = 0; y < r.height(); ++y)
    for (int x = 0; x < r.width(); ++x) out.at(x, y, 1) = r.at(x, y);
  return out;
}

std::string sanitize(std::string s) {
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.') ch = '_';
  return s;
}

int run_wound(const WoundArgs& a) {
  Stopwatch total, watch;
  Timings timings;
  // 1. Everything that can fail on bad input, before any output is written.
  TriMesh mesh;
  std::string mesh_source = a.mesh;
  if (!a.mesh.empty()) {
    MeshImportOptions import_options;
    import_options.unit = a.unit;
    import_options.scale = a.mesh_scale;
    mesh = import_mesh(a.mesh, import_options);
    if (!mesh.has_uvs()) {
      throw InputError(a.mesh, "mesh", "has no texture coordinates (UVs); a wound is painted into UV maps");
    }
  } else if (a.builtin == "forearm-uv") {
    mesh = make_forearm_uv().mesh;
    mesh_source = "built-in forearm-uv phantom";
  } else {
    mesh = make_uv_cylinder();
    mesh_source = "built-in UV cylinder";
  }
  timings.add("mesh", watch.lap());
  std::optional<std::string> type_override;
  if (!a.type.empty()) type_override = a.type;
  JobDocument job_doc = a.strokes.empty() ? JobDocument::parse(default_strokes_json(mesh), "default strokes")
                                          : JobDocument::load(a.strokes);
  WoundJob job = read_wound_job(job_doc.root(), mesh, type_override);
  job_doc.check_all_used();
  if (!a.distance.empty()) job.canvas.distance = a.distance == "uv" ? DistanceMode::uv : DistanceMode::surface;
  if (!a.shape.empty()) job.canvas.shape = a.shape == "convex_hull" ? ShapeMode::convex_hull : ShapeMode::strokes;
  const std::vector<double> times = a.times.empty() ? std::vector<double>{} : parse_durations(a.times, "--times");
  const int n = a.resolution;
  Image upper, lower;
  default_skin_maps(n, n, a.seed, upper, lower);
  std::shared_ptr<const Image> mesh_texture = a.mesh.empty() ? nullptr : load_base_texture(mesh);
  if (!a.upper_skin.empty()) {
    upper = read_png(a.upper_skin).resized(n, n).with_channels(4);
  } else if (mesh_texture) {
    upper = mesh_texture->resized(n, n).with_channels(4);
  }
  if (!a.lower_skin.empty()) {
    lower = read_png(a.lower_skin).resized(n, n).with_channels(4);
  } else if (!a.upper_skin.empty() || mesh_texture) {
    // Dermis under the given skin: redder and darker.
    lower = upper;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const Vec4f u = upper.rgba(x, y);
        lower.set_rgba(x, y, Vec4f(u.x() * 1.05f, u.y() * 0.7f, u.z() * 0.75f, 1.0f));
      }
  }
  const UvRaster raster = rasterize_uv(mesh, n, n);
  job.canvas.seed = a.seed;
  job.canvas.texels_per_mm = a.texels_per_mm;
  job.canvas.reach_mm = job.type == "abrasion" ? job.abrasion.reach_mm() : bruise_reach_mm();
  auto canvas = std::make_shared<WoundCanvas>(make_wound_canvas(mesh, raster, job.strokes, upper, lower, job.canvas));
  timings.add("canvas", watch.lap());
  Timeline timeline(job.timeline);
  timeline.render(canvas);
  timings.add("key positions", watch.lap());

  // 2. Outputs.
  RunFolder run(a.out, "wound");
  run.set_job(job_doc.resolved());
  run.set_seed(a.seed);
  const float skin_reflection = job.type == "abrasion" ? job.abrasion.skin_reflection : 0.25f;
  const MapSet skin = skin_map_set(upper, skin_reflection);
  const double tpm = canvas->texels_per_mm;
  nlohmann::json description = timeline.describe();
  description["type"] = job.type;
  description["mesh"] = mesh_source;
  description["seed"] = a.seed;
  description["key_files"] = nlohmann::json::array();
  // Key positions (each distinct one once) and requested times, as full map sets.
  struct Shot {
    std::string caption, prefix;
    MapSet maps;
  };
  std::vector<Shot> keys, shots;
  const auto& entries = timeline.entries();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i > 0 && timeline.same_maps(i, i - 1)) continue;
    Shot s{entries[i].label + " (" + format_injury_time(entries[i].time_s) + ")",
           "key" + std::to_string(i) + "_" + sanitize(entries[i].key->name()), skin};
    timeline.write_entry_full(i, s.maps);
    keys.push_back(std::move(s));
  }
  for (double t : times) {
    Shot s{format_injury_time(t) + " after injury", "time_" + sanitize(format_injury_time(t)), skin};
    timeline.sample_full(t, s.maps);
    shots.push_back(std::move(s));
  }
  for (auto* list : {&keys, &shots}) {
    for (const auto& s : *list) {
      for (const auto& f : write_map_set(s.maps, run.file("maps"), s.prefix, tpm, job.abrasion.scab_height_mm)) {
        run.add_output("maps/" + f);
      }
      description[list == &keys ? "key_files" : "time_files"].push_back(s.prefix);
    }
  }
  timings.add("maps", watch.lap());
  // GLBs: the displaced mesh with the maps as PBR material, one per requested time (or the last key).
  for (const auto& s : shots.empty() ? std::vector<Shot>{keys.back()} : shots) {
    GltfScene scene;
    GltfMeshNode node;
    node.name = "skin_" + s.prefix;
    node.mesh = displaced(mesh, s.maps.height_mm);
    node.mesh.material.name = "wound";
    node.textures.base_color_png = encode_png(s.maps.color.with_channels(3));
    node.textures.normal_png = encode_png(normal_from_height(s.maps.height_mm, tpm));
    node.textures.metallic_roughness_png = encode_png(metallic_roughness(s.maps.reflection));
    scene.nodes.push_back(std::move(node));
    write_gltf(run.file("wound_" + s.prefix + ".glb"), scene);
    run.add_output("wound_" + s.prefix + ".glb");
  }
  timings.add("glb", watch.lap());
  // Close-up renders: camera along the surface normal at the wound's centre.
  if (a.picture_size > 0) {
    Vec3 centre = Vec3::Zero();
    std::size_t count = 0;
    for (const auto& st : job.strokes)
      for (const auto& p : st.points) centre += p, ++count;
    centre /= static_cast<double>(count);
    const std::vector<Vec3> normals =
        mesh.normals.size() == mesh.positions.size() ? mesh.normals : vertex_normals(mesh);
    std::size_t best = 0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      if ((mesh.positions[i] - centre).squaredNorm() < (mesh.positions[best] - centre).squaredNorm()) best = i;
    const Vec3 surface = mesh.positions[best];
    // Look from outside: scans may carry inward normals, so point the normal away from the mesh's centroid.
    Vec3 centroid = Vec3::Zero();
    for (const auto& p : mesh.positions) centroid += p;
    centroid /= static_cast<double>(mesh.positions.size());
    Vec3 normal = normals[best].normalized();
    if (normal.dot(surface - centroid) < 0.0) normal = -normal;
    const double view = std::max(30.0, canvas->closing_distance_mm + 2.0 * std::min(job.canvas.reach_mm, 15.0)) * 1.3;
    const double distance = view / (2.0 * std::tan(15.0 * M_PI / 180.0));
    Vec3 up = std::abs(normal.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitY();
    const Camera camera = Camera::look_at(surface + normal * distance, surface, up, 30.0);
    RenderSettings settings;
    settings.width = settings.height = a.picture_size;
    settings.samples_per_pixel = a.samples;
    settings.seed = a.seed;
    // The displaced mesh with one map set, seen `from` a camera.
    auto render_maps = [&](const MapSet& maps, const Camera& from) {
      Scene scene;
      SurfaceMaterial material = SurfaceMaterial::skin();
      material.colour_source = ColourSource::texture;
      material.base_colour = Vec3f(1, 1, 1);
      material.base_texture = std::make_shared<Image>(maps.color);
      material.normal_map = std::make_shared<Image>(normal_from_height(maps.height_mm, tpm));
      scene.add(displaced(mesh, maps.height_mm), material, "skin");
      scene.camera = from;
      return Renderer(scene).render(from, settings);
    };
    auto render_shots = [&](const std::vector<Shot>& list) {
      std::vector<SheetCell> cells;
      for (const auto& s : list) cells.push_back({render_maps(s.maps, camera), s.caption});
      return cells;
    };
    const auto key_cells = render_shots(keys);
    write_png(run.file("timeline_keys.png"), make_sheet(key_cells, std::min<int>(5, static_cast<int>(key_cells.size())),
                                                        "forensim wound: " + job.type + " key positions"));
    run.add_output("timeline_keys.png");
    // The whole mesh, seen from the wound's side, at the key with the most relief (the abrasion's scab; the
    // middle key when none has any): where on the body the wound sits, beside the close-ups.
    std::size_t relief = keys.size() / 2;
    float most = 0.0f;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto& h = keys[i].maps.height_mm.data();
      const float top = h.empty() ? 0.0f : *std::max_element(h.begin(), h.end());
      if (top > most) most = top, relief = i;
    }
    const BoundingBox box = bounding_box(mesh.positions);
    const double far = 1.1 * (box.max - box.min).norm() / (2.0 * std::tan(15.0 * M_PI / 180.0));
    const Camera overview = Camera::look_at(surface + normal * far, surface, up, 30.0);
    write_png(run.file("overview.png"),
              make_sheet({{render_maps(keys[relief].maps, overview), keys[relief].caption + ", whole mesh"}}, 1,
                         "forensim wound: " + job.type));
    run.add_output("overview.png");
    if (!shots.empty()) {
      const auto time_cells = render_shots(shots);
      write_png(run.file("timeline_times.png"),
                make_sheet(time_cells, std::min<int>(5, static_cast<int>(time_cells.size())),
                           "forensim wound: " + job.type + " after injury"));
      run.add_output("timeline_times.png");
    }
    timings.add("renders", watch.lap());
  }
  run.write("timeline.json", description.dump(2));
  for (const auto& [stage, seconds] : timings.stages()) run.timings().add(stage, seconds);
  run.facts()["texels_per_mm"] = tpm;
  run.facts()["wound_texels"] = canvas->wound_texels;
  run.facts()["closing_distance_mm"] = canvas->closing_distance_mm;
  run.write_record();
  std::printf("wrote %s (%s, %zu key positions, %zu times, %s)\n", run.path().string().c_str(), job.type.c_str(),
              keys.size(), shots.size(), format_seconds(total.seconds()).c_str());
  return 0;
}

const RegisterCommand wound_command{
    "wound", [](CLI::App& app) {
      auto* sub = app.add_subcommand("wound", "Paint a wound on a skin mesh with UVs and write its healing timeline");
      auto a = std::make_shared<WoundArgs>();
      sub->add_option("-o,--out", a->out, "Output folder")->required();
      sub->add_option("--mesh", a->mesh, "Skin mesh with UVs (any format Assimp reads); default: built-in");
      sub->add_option("--unit", a->unit, "Unit of the mesh file: auto, m, cm, mm or in");
      sub->add_option("--mesh-scale", a->mesh_scale,
                      "Millimetres per mesh unit (overrides --unit; for scans in arbitrary units)")
          ->check(CLI::Range(0.0, 1e6));
      sub->add_option("--builtin", a->builtin, "Built-in mesh without --mesh: forearm-uv or cylinder")
          ->check(CLI::IsMember({"forearm-uv", "cylinder"}));
      sub->add_option("--strokes", a->strokes,
                      "Wound job JSON: strokes (3D, UV or screen points), shape, distance, keys");
      sub->add_option("--type", a->type, "Wound type (overrides the job's)")
          ->check(CLI::IsMember({"abrasion", "bruise"}));
      sub->add_option("--distance", a->distance, "Distances on the surface in 3D (default) or in UV space")
          ->check(CLI::IsMember({"surface", "uv"}));
      sub->add_option("--shape", a->shape, "Wound shape: strokes (default) or convex_hull (the thesis's)")
          ->check(CLI::IsMember({"strokes", "convex_hull"}));
      sub->add_option("--upper-skin", a->upper_skin, "Healthy skin colour map (PNG)");
      sub->add_option("--lower-skin", a->lower_skin, "Skin under the epidermis colour map (PNG)");
      sub->add_option("--resolution", a->resolution, "Texture size in texels")->check(CLI::Range(32, 8192));
      sub->add_option("--texels-per-mm", a->texels_per_mm, "Texture density (default: from the mesh's UVs)")
          ->check(CLI::Range(0.0, 1000.0));
      sub->add_option("--times", a->times, "Times after injury to write, e.g. 1h,36h,5d,2w");
      sub->add_option("--seed", a->seed, "Seed of the wound's noise (same seed, same wound)");
      sub->add_option("--picture-size", a->picture_size, "Pixels per rendered view (0 = no renders)")
          ->check(CLI::Range(0, 4096));
      sub->add_option("--samples", a->samples, "Samples per pixel of the renders")->check(CLI::Range(1, 256));
      return [a]() { return run_wound(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
