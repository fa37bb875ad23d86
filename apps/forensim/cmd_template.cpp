// forensim template build: a template head for forensim reconstruct made from a real head, a CT (its skin, its
// skull and the skull's landmarks) or a head mesh (with its texture and skin landmarks), by carrying the built-in
// template onto it (craniofacial/template_build.hpp). Writes the template file and what shows it.

#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "craniofacial/face_evaluation.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/template_build.hpp"
#include "craniofacial/template_file.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "image/jpeg_io.hpp"
#include "image/png_io.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/mesh_import.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "pictures.hpp"
#include "render/sheet.hpp"
#include "template_cmd.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

nlohmann::json report_json(const TemplateBuildReport& r) {
  nlohmann::json left = nlohmann::json::array();
  for (const auto& [name, why] : r.pairs_left) left.push_back({{"pair", name}, {"why", why}});
  return {{"pairs_from_skull", r.pairs_from_skull},   {"pairs_from_skin", r.pairs_from_skin},
          {"pairs_unscanned", r.pairs_unscanned},     {"pairs_left", left},
          {"warp_landmarks", r.warp_landmarks},       {"vertices_conformed", r.vertices_conformed},
          {"vertices_warped", r.vertices_warped},     {"mean_conform_mm", r.mean_conform_mm},
          {"flipped_triangles", r.flipped_triangles}, {"texture_baked", r.texture_baked}};
}

}  // namespace

int run_template_build(const TemplateArgs& a) {
  check_output_path(a.out, OutputKind::folder);
  if (a.builtin) {
    if (!a.ct.empty() || !a.head.empty()) throw Error("--builtin takes no --ct or --head", ErrorKind::usage);
    Stopwatch watch;
    const TemplateHead head = make_template_head(template_head_options(a.detail));
    RunFolder run(a.out, "template build");
    run.write("template.cbor", encode_template_head(head));
    run.set_job({{"builtin", true}, {"detail", a.detail}});
    run.timings().add("built-in template", watch.seconds());
    run.write_record();
    std::printf("wrote %s/template.cbor: the built-in template (%s), %zu skin vertices; %s\n", a.out.c_str(),
                a.detail.c_str(), head.skin.vertex_count(), format_seconds(watch.seconds()).c_str());
    return 0;
  }
  if (a.ct.empty() == a.head.empty()) {
    throw Error("give one of --ct (a CT volume or 'phantom') and --head (a head mesh), or --builtin", ErrorKind::usage);
  }
  if (!a.ct.empty() && (!a.texture.empty() || !a.skin_landmarks.empty())) {
    throw Error("--texture and --skin-landmarks belong to --head; a CT's skin points come from its skull",
                ErrorKind::usage);
  }
  if (!a.head.empty() && a.skin_landmarks.empty()) {
    throw Error(
        "--head needs --skin-landmarks: the head's skin landmarks (3D Slicer .mrk.json or CSV, named as the "
        "template's: se', prn', pg', zy'_L, ...)",
        ErrorKind::usage);
  }
  Stopwatch watch, total;
  Timings timings;
  // Every input file (volume or head, landmarks, texture) is read before the built-in template is built: a
  // bad file is an error at once.
  std::optional<ScalarGrid> ct_volume;
  std::optional<ImportedMesh> head_mesh;
  LandmarkSet landmarks_read;  // --landmarks (with --ct) or --skin-landmarks (with --head), unless auto
  Image texture_read;          // --texture
  const bool phantom = a.ct == "phantom";
  if (!a.ct.empty()) {
    if (!phantom && !std::filesystem::exists(a.ct)) throw IoError(a.ct, "does not exist");
    ct_volume = phantom ? make_ct_head_phantom() : read_volume(a.ct);
    if (a.landmarks != "auto") landmarks_read = read_landmarks(a.landmarks);
  } else {
    MeshImportOptions units;
    units.unit = a.unit;
    units.scale = a.mesh_scale;
    head_mesh = import_mesh_with_textures(a.head, units);
    if (a.skin_landmarks != "auto") landmarks_read = read_landmarks(a.skin_landmarks);
    if (!a.texture.empty()) texture_read = read_image(a.texture);
  }
  timings.add("input", watch.lap());
  TemplateHead base = make_template_head(template_head_options(a.detail));
  timings.add("built-in template", watch.lap());

  TemplateBuildInput input;
  nlohmann::json inputs;
  if (!a.ct.empty()) {
    const ScalarGrid& volume = *ct_volume;
    const std::string source = phantom ? std::string("built-in CT head phantom") : a.ct;
    SkullInputOptions skull_options;
    skull_options.bone_iso_value = a.bone_iso;
    skull_options.half_maximum_height = !a.bone_iso;
    Skull skull = skull_from_volume(volume, source, skull_options);
    timings.add("skull", watch.lap());
    if (a.landmarks == "auto") {
      ScanLandmarkDetection found = detect_scan_landmarks(base, skull.mesh, skull.field_of_view);
      if (found.completion) skull.mesh = found.completion->mesh;
      input.skull_landmarks = found.detection.landmarks;
      for (const auto& [name, reason] : found.detection.left_out) {
        std::printf("landmark %s left out: %s\n", name.c_str(), reason.c_str());
      }
      timings.add("landmark detection", watch.lap());
    } else {
      input.skull_landmarks = std::move(landmarks_read);
    }
    double skin_iso = 0.0;
    input.skin = real_face_surface(volume, source, {}, &skin_iso);
    input.skin_view = skull.field_of_view;
    input.skull = skull.mesh;
    input.source = "CT " + source;
    inputs = {{"ct", source},
              {"skull_triangles", skull.mesh.triangle_count()},
              {"skull_notes", skull.notes},
              {"skin_iso", skin_iso},
              {"skin_triangles", input.skin.triangle_count()},
              {"landmarks", a.landmarks},
              {"skull_landmarks", input.skull_landmarks.size()}};
    if (skull.iso_value) inputs["bone_iso"] = *skull.iso_value;
    timings.add("skin", watch.lap());
  } else {
    ImportedMesh& imported = *head_mesh;
    input.skin = std::move(imported.mesh);
    if (!a.texture.empty()) {
      input.texture = std::move(texture_read);
    } else {
      for (const EmbeddedTexture& t : imported.textures) {
        if (t.role != "base_color") continue;
        input.texture = decode_image(t.bytes, a.head + " texture");
        break;
      }
    }
    if (!input.texture.empty() && !input.skin.has_uvs()) {
      throw InputError(a.head, "texture coordinates", "the head mesh has none: its texture cannot be carried");
    }
    double registration_rms = -1.0;
    if (a.skin_landmarks == "auto") {
      input.skin_landmarks = skin_landmarks_by_registration(base, input.skin, &registration_rms);
      timings.add("skin landmarks by registration", watch.lap());
    } else {
      input.skin_landmarks = std::move(landmarks_read);
    }
    input.source = "head mesh " + a.head;
    inputs = {{"head", a.head},
              {"skin_triangles", input.skin.triangle_count()},
              {"texture", a.texture.empty() ? (input.texture.empty() ? "none" : "embedded") : a.texture},
              {"skin_landmarks", a.skin_landmarks},
              {"skin_landmark_count", input.skin_landmarks.size()}};
    if (registration_rms >= 0.0) inputs["registration_rms_mm"] = registration_rms;
    timings.add("head mesh", watch.lap());
  }

  TemplateBuildOptions options;
  options.texture_size = a.texture_size;
  const TemplateBuild built = build_template_head(base, input, options);
  timings.add("template build", watch.lap());
  const TemplateHead& head = built.head;
  const TemplateBuildReport& report = built.report;

  RunFolder run(a.out, "template build");
  run.write("template.cbor", encode_template_head(head));
  // The template as a scene other tools open: the skin (its texture when it has one) and the skull.
  GltfScene scene;
  GltfMeshNode skin_node;
  skin_node.name = "template skin";
  skin_node.mesh = head.skin;
  skin_node.mesh.material.name = "skin";
  if (!head.texture_png.empty()) skin_node.textures.base_color_png = head.texture_png;
  scene.nodes.push_back(std::move(skin_node));
  scene.nodes.push_back(skull_gltf_node("template skull", head.skull));
  write_gltf(run.file("template.glb"), scene);
  run.add_output("template.glb");
  LandmarkSet skull_set("template skull"), skin_set("template skin");
  for (const TemplateLandmarkPair& p : head.landmarks) {
    if (!skull_set.contains(p.bone_name)) skull_set.add({p.bone_name, p.skull, LandmarkSource::detected, 1.0});
    skin_set.add({p.skin_name, p.skin, LandmarkSource::detected, 1.0});
  }
  for (const TemplateSkinLandmark& l : head.skin_landmarks) {
    skin_set.add({l.name, l.position, LandmarkSource::detected, 1.0});
  }
  write_landmarks(run.file("template_skull_landmarks.mrk.json"), skull_set);
  run.add_output("template_skull_landmarks.mrk.json");
  write_landmarks(run.file("template_skin_landmarks.mrk.json"), skin_set);
  run.add_output("template_skin_landmarks.mrk.json");
  timings.add("write", watch.lap());

  if (a.picture_size > 0) {
    RenderSettings settings;
    settings.width = settings.height = a.picture_size;
    const ViewAxes axes = axes_from_name("lps");
    auto skin_ptr = std::make_shared<const TriMesh>(head.skin);
    auto skull_ptr = std::make_shared<const TriMesh>(head.skull);
    Scene overlay = skin_over_bone_scene(skin_ptr, skull_ptr, 0.35, axes);
    std::vector<std::pair<Vec3, Vec3>> vectors;
    for (const TemplateLandmarkPair& p : head.landmarks) vectors.emplace_back(p.skull, p.skin);
    add_depth_vectors(overlay, vectors);
    std::vector<SheetCell> cells;
    cells.push_back({render_view(overlay, settings, "front", axes), "front"});
    cells.push_back({render_view(overlay, settings, "left", axes), "side"});
    Scene face;
    face.environment.up = axes.up;
    SurfaceMaterial material = SurfaceMaterial::skin();
    if (!head.texture_png.empty()) {
      material.colour_source = ColourSource::texture;
      material.base_colour = Vec3f(1, 1, 1);
      material.base_texture = std::make_shared<Image>(decode_png(head.texture_png, "template texture"));
    }
    face.add(skin_ptr, material, "skin");
    cells.push_back({render_view(face, settings, "three_quarter", axes), "template skin"});
    run.write("template.png", encode_png(make_sheet(cells, 3, "forensim template build")));
    timings.add("renders", watch.lap());
  }

  nlohmann::json job = {{"ct", a.ct},
                        {"head", a.head},
                        {"texture", a.texture},
                        {"skin_landmarks", a.skin_landmarks},
                        {"landmarks", a.landmarks},
                        {"unit", a.unit},
                        {"mesh_scale", a.mesh_scale},
                        {"detail", a.detail},
                        {"texture_size", a.texture_size},
                        {"picture_size", a.picture_size}};
  if (a.bone_iso) job["bone_iso"] = *a.bone_iso;
  run.set_job(job);
  run.facts()["inputs"] = inputs;
  run.facts()["build"] = report_json(report);
  run.facts()["template"] = {{"source", head.source},
                             {"skin_vertices", head.skin.vertex_count()},
                             {"skull_triangles", head.skull.triangle_count()},
                             {"landmark_pairs", head.landmarks.size()},
                             {"muscles", head.muscles.size()},
                             {"own_texture", !head.texture_png.empty()}};
  // The template's own tissue depths (the subject's, for a CT), beside the built-in template's.
  nlohmann::json pairs = nlohmann::json::array();
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    const TemplateLandmarkPair& p = head.landmarks[i];
    pairs.push_back({{"bone", p.bone_name},
                     {"skin", p.skin_name},
                     {"depth_mm", p.depth_mm},
                     {"built_in_depth_mm", base.landmarks[i].depth_mm}});
  }
  run.facts()["pairs"] = pairs;
  for (const auto& [stage, seconds] : timings.stages()) run.timings().add(stage, seconds);
  run.write_record();
  std::printf(
      "wrote %s/template.cbor: %zu skin vertices (%zu on the head's skin, %zu carried by the warp, mean "
      "move %.2f mm, %zu triangles turned over), %zu pairs (%zu measured on the skull, %zu given on the "
      "skin, %zu kept from the warp)%s; %s\n",
      a.out.c_str(), head.skin.vertex_count(), report.vertices_conformed, report.vertices_warped,
      report.mean_conform_mm, report.flipped_triangles, head.landmarks.size(), report.pairs_from_skull.size(),
      report.pairs_from_skin.size(), report.pairs_left.size(),
      report.texture_baked ? ", texture baked on the atlas" : "", format_seconds(total.seconds()).c_str());
  for (const auto& [name, why] : report.pairs_left) std::printf("  pair %s: %s\n", name.c_str(), why.c_str());
  return 0;
}

namespace {

const RegisterCommand template_command{
    "template", [](CLI::App& app) {
      auto* sub = app.add_subcommand("template", "Template heads for forensim reconstruct");
      sub->require_subcommand(1);
      auto* build =
          sub->add_subcommand("build",
                              "Make a template head from a CT (skin, skull and its landmarks) or a head mesh (with its "
                              "texture and skin landmarks)");
      auto a = std::make_shared<TemplateArgs>();
      build->add_option("-o,--out", a->out, "Output folder (template.cbor, template.glb, landmarks, template.png)")
          ->required();
      build->add_flag("--builtin", a->builtin,
                      "Write the built-in template at --detail to a file (read quicker than it is built)");
      build->add_option("--ct", a->ct, "CT volume holding skin and skull, or 'phantom' (the built-in CT)");
      build->add_option("--head", a->head, "Head mesh (any format Assimp reads; its UVs and texture are kept)");
      build->add_option("--texture", a->texture, "Base-colour map of the head mesh (PNG or JPEG)");
      build->add_option(
          "--skin-landmarks", a->skin_landmarks,
          "Skin landmarks on the head mesh (.mrk.json or .csv, the template's names: se', prn', ...), or auto");
      build->add_option("--landmarks", a->landmarks, "The CT skull's landmarks: auto (detected) or a file");
      build->add_option("--unit", a->unit, "Unit of the head mesh: auto, m, cm, mm or in")
          ->check(CLI::IsMember({"auto", "m", "cm", "mm", "in"}));
      build->add_option("--mesh-scale", a->mesh_scale, "Millimetres per head-mesh unit (overrides --unit)")
          ->check(CLI::Range(0.0, 1e6));
      build->add_option("--bone-iso", a->bone_iso, "CT bone iso-value (default: the half-maximum bone edge)");
      build->add_option("--detail", a->detail, "The built-in template carried onto the head: full or coarse")
          ->check(CLI::IsMember({"full", "coarse"}));
      build->add_option("--texture-size", a->texture_size, "Baked texture size (texels per side)")
          ->check(CLI::Range(16, 8192));
      build->add_option("--picture-size", a->picture_size, "Pixels per rendered view (0 = no renders)")
          ->check(CLI::Range(0, 4096));
      return [a, build]() {
        if (!build->parsed()) throw Error("forensim template: give a subcommand (build)", ErrorKind::usage);
        return run_template_build(*a);
      };
    }};

}  // namespace
}  // namespace forensim::cli
