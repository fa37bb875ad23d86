// forensim reconstruct: rebuilds a face from a skull (Kähler, Haber and Seidel 2003): skull landmarks with
// tissue-depth vectors from a published table, the RBF warp of the template head onto their skin points (with
// interpolated cranium and mandible pairs), the nose and mouth guides, and the outputs: the head (textured GLB
// and OBJ) with the skull, skull and skin landmarks (.mrk.json), pictures of the skin over the skull with the
// depth vectors, the skull/skin violations, and a provenance record. Everything is computed before the output
// folder is created, so bad input writes nothing.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/job.hpp"
#include "core/parallel.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "craniofacial/face_evaluation.hpp"
#include "craniofacial/face_expression.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/reconstruction_uncertainty.hpp"
#include "craniofacial/skull_completion.hpp"
#include "craniofacial/skull_guides.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/template_carry.hpp"
#include "craniofacial/template_file.hpp"
#include "craniofacial/template_head.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "geometry/mesh_measures.hpp"
#include "image/png_io.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_io/obj_writer.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "phantoms/skin_maps.hpp"
#include "pictures.hpp"
#include "reconstruct_job.hpp"
#include "render/colour_bar.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "tet_io/vtu_writer.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

struct ReconstructArgs {
  ReconstructJob job;
  std::string job_file;
  std::string guides_file;
  std::string out;
  bool no_interpolated = false;
  bool no_carry = false;
  bool evaluate = false;
  bool measure_guides = false;
  std::string expressions;  ///< --expressions: comma-separated presets, or "none"
};

/// The head frame automatic landmarks were refined in: origin and axes in the skull's coordinates (mm).
nlohmann::json head_frame_json(const HeadFrame& frame) {
  const auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  return {{"origin_mm", vec(frame.origin)},
          {"x_left", vec(frame.axes.col(0))},
          {"y_posterior", vec(frame.axes.col(1))},
          {"z_superior", vec(frame.axes.col(2))},
          {"perpendicularity_deg", frame.perpendicularity_deg}};
}

std::string table_name(const std::string& name) {
  if (name == "rhine_1983") return "rhine_1983_sw_native_american_female_normal";
  return name;
}

int run_reconstruct(ReconstructArgs& a, CLI::App& sub) {
  check_output_path(a.out, OutputKind::folder);
  // 1. The job: the command line's values, overridden by a job file where it gives them, and the command line
  // again where an option was typed explicitly.
  ReconstructJob cli_job = a.job;
  std::filesystem::path base;
  JobDocument doc = JobDocument::empty("command line");
  if (!a.job_file.empty()) {
    doc = JobDocument::load(a.job_file);
    base = std::filesystem::path(a.job_file).parent_path();
  }
  ReconstructJob job = read_reconstruct_job(doc.root(), cli_job, base);
  doc.check_all_used();
  auto typed = [&](const char* option) { return sub.count(option) > 0; };
  if (typed("--skull")) job.skull = cli_job.skull;
  if (typed("--ct")) job.ct = cli_job.ct;
  if (typed("--unit")) job.unit = cli_job.unit;
  if (typed("--mesh-scale")) job.mesh_scale = cli_job.mesh_scale;
  if (typed("--bone-iso")) job.bone_iso = cli_job.bone_iso;
  if (typed("--bone-edge")) job.bone_edge = cli_job.bone_edge;
  if (typed("--landmarks")) job.landmarks = cli_job.landmarks;
  if (typed("--table")) job.table = cli_job.table;
  if (typed("--sex")) job.sex = cli_job.sex;
  if (typed("--population")) job.population = cli_job.population;
  if (typed("--build")) job.build = cli_job.build;
  if (typed("--build-sd")) job.build_sd = cli_job.build_sd;
  if (typed("--seed")) job.seed = cli_job.seed;
  if (typed("--template-detail")) job.template_detail = cli_job.template_detail;
  if (typed("--template")) job.template_file = cli_job.template_file;

  if (typed("--axes")) job.axes = cli_job.axes;
  if (typed("--texture-size")) job.texture_size = cli_job.texture_size;
  if (typed("--picture-size")) job.picture_size = cli_job.picture_size;
  if (typed("--samples")) job.samples = cli_job.samples;
  if (typed("--uncertainty")) job.uncertainty_samples = cli_job.uncertainty_samples;
  if (typed("--expressions")) job.expressions = parse_expression_list(a.expressions, "--expressions");
  if (a.no_interpolated) job.interpolated_landmarks = false;
  if (a.no_carry) job.carry_template = false;
  if (a.evaluate) job.evaluate = true;
  if (a.measure_guides) job.measure_guides = true;
  nlohmann::json guides_record = nullptr;
  if (!a.guides_file.empty()) {
    JobDocument guides_doc = JobDocument::load(a.guides_file);
    job.guides = read_face_guides(guides_doc.root());
    guides_doc.check_all_used();
    job.has_guides = any_guide(job.guides);
    guides_record = guides_doc.resolved();
    guides_record["file"] = a.guides_file;
  } else if (doc.resolved().contains("guides")) {
    guides_record = doc.resolved()["guides"];
  }

  const nlohmann::json facts =
      run_reconstruction(job, a.out, reconstruct_job_record(job, doc.resolved()), guides_record);
  std::printf("wrote %s (%d landmark pairs + %d interpolated + %d correction; skull/skin violations %d -> %d; %s)\n",
              a.out.c_str(), facts["given_pairs"].get<int>(), facts["interpolated_pairs"].get<int>(),
              facts["correction_pairs"].get<int>(), facts["violations_before"].get<int>(),
              facts["violations_after"].get<int>(), format_seconds(facts["seconds_total"].get<double>()).c_str());
  if (facts.contains("evaluation_rms_mm")) {
    std::printf(
        "evaluation against the real face: mean %.2f mm, RMS %.2f mm, signed mean %+.2f mm, %.1f %% within "
        "2.5 mm\n",
        facts["evaluation_mean_abs_mm"].get<double>(), facts["evaluation_rms_mm"].get<double>(),
        facts["evaluation_signed_mean_mm"].get<double>(), facts["evaluation_within_percent"].get<double>());
  }
  return 0;
}

}  // namespace

nlohmann::json run_reconstruction(const ReconstructJob& job, const std::filesystem::path& out,
                                  const nlohmann::json& resolved_job, const nlohmann::json& guides_record) {
  Stopwatch total, watch;
  Timings timings;
  // 2. Table and depths (cheap, checked first).
  const TissueDepthTable table = tissue_depth_table(table_name(job.table));
  TissueDepthQuery query{job.sex, job.population, ""};
  TissueDepths depths;
  std::string build_method;
  if (job.build.empty()) {
    depths = select_tissue_depths(table, query);
  } else {
    const BuildVariants variants = build_variants(table, query, job.build_sd);
    depths = job.build == "slender" ? variants.slender : job.build == "obese" ? variants.obese : variants.normal;
    build_method = variants.method;
  }

  // Expression names: checked (closest preset named) before anything costly.
  for (std::size_t i = 0; i < job.expressions.size(); ++i) {
    static_cast<void>(expression_preset(job.expressions[i]));
    for (std::size_t k = 0; k < i; ++k)
      if (job.expressions[k] == job.expressions[i]) throw InputError("expressions", job.expressions[i], "listed twice");
  }

  // 3. Skull and landmarks (files are read before the template is built, so their errors come quickly).
  const bool builtin_skull = job.ct.empty() && job.skull == "builtin";
  const bool phantom_ct = job.ct == "phantom";
  // Landmarks: a file, the template's own (for skulls in the template's frame: the built-in skull and the CT
  // phantom, their default), or detected on the skull with the template's skull as the reference (the default
  // for any other skull).
  std::string landmark_mode = job.landmarks;
  if (landmark_mode.empty()) landmark_mode = builtin_skull || phantom_ct ? "template" : "auto";
  if (landmark_mode == "template" && !builtin_skull && !phantom_ct) {
    throw InputError("--landmarks", "template",
                     "only the built-in skull and the CT phantom carry the template's landmarks; give a .mrk.json or "
                     "CSV file, or 'auto' to detect them");
  }
  if (job.evaluate && (builtin_skull || (job.ct.empty() && !is_volume_path(job.skull)))) {
    throw InputError("--evaluate", builtin_skull ? "built-in skull" : job.skull,
                     "the evaluation needs a CT that holds the face (its skin); a mesh skull has none");
  }
  std::optional<LandmarkSet> file_landmarks;
  if (landmark_mode != "template" && landmark_mode != "auto") file_landmarks = read_landmarks(landmark_mode);
  timings.add("inputs", watch.lap());

  // The template and the skull are independent: a CT's skull is read and extracted while the template is built
  // (each stage's own time is recorded; they overlap).
  const TemplateHeadOptions template_options = template_head_options(job.template_detail);
  TemplateHead head;
  Skull skull;
  std::optional<ScalarGrid> volume;
  const SkullInputOptions skull_options = skull_input_options(job);
  const std::string skull_path = job.ct.empty() ? job.skull : job.ct;
  // The skull's file (a CT or a mesh) is read before the template build starts beside the skull's extraction: a
  // bad file is an error in a tenth of a second, not after the template.
  std::optional<ImportedMesh> skull_file;
  Stopwatch skull_read;
  if (!builtin_skull && !phantom_ct) {
    if (is_volume_path(skull_path)) {
      if (!std::filesystem::exists(skull_path)) throw IoError(skull_path, "does not exist");
      volume = read_volume(skull_path);
    } else {
      skull_file = import_mesh_with_textures(skull_path, skull_options.mesh_units);
    }
  }
  double template_s = 0.0, skull_s = skull_read.seconds();
  const bool template_from_file = !job.template_file.empty();
  const auto build_template = [&] {
    Stopwatch part;
    head = template_from_file ? read_template_head(job.template_file) : make_template_head(template_options);
    template_s = part.seconds();
  };
  const auto read_skull = [&] {
    Stopwatch part;
    // A CT is kept: the evaluation takes the real face from it.
    if (phantom_ct) {
      volume = make_ct_head_phantom();
      skull = skull_from_volume(*volume, "built-in CT head phantom", skull_options);
    } else if (is_volume_path(skull_path)) {
      skull = skull_from_volume(*volume, skull_path, skull_options);
    } else {
      skull = skull_from_mesh(std::move(skull_file->mesh), skull_path, skull_options);
      skull.mm_per_unit = skull_file->mm_per_unit;
    }
    skull_s += part.seconds();
  };
  std::optional<LandmarkDetection> detection;
  std::optional<SkullCompletion> completion;
  bool registered_skull_is_fitted = true;  // the detection's registration maps the fitted template's skull
  // Automatic landmarks: the template's skull registered onto the skull, its landmarks refined there; landmarks the
  // scan did not see lie on the registered template, whose missing part completes the skull.
  double detection_s = 0.0;  // with the skull's completion
  const auto detect = [&](const TemplateHead& reference) {
    Stopwatch part;
    ScanLandmarkDetection found = detect_scan_landmarks(reference, skull.mesh, skull.field_of_view);
    detection = std::move(found.detection);
    completion = std::move(found.completion);
    detection_s = part.lap();
    const std::size_t unseen = found.unseen;
    if (completion) {
      skull.mesh = completion->mesh;
      skull.notes.push_back(fmt::format(
          "{} landmarks lie outside the scan: completed with the registered template skull ({} triangles, {} cap "
          "triangles of the cut dropped)",
          unseen, completion->reference_triangles, completion->cap_triangles));
    }
  };
  if (builtin_skull) {
    build_template();
    skull.mesh = head.skull;
    skull.source = "built-in template skull (head phantom)";
    skull.kind = "builtin";
    if (landmark_mode == "auto") detect(head);
  } else if (landmark_mode == "auto" && template_from_file) {
    // The skull's landmarks are found with the built-in template's skull, the reference the registration is made
    // for (a template built from a scan has a skull warped under its skin, or a CT's partial one); the template
    // file's skin and pairs are what is fitted. The file is read and the skull read beside the reference's build.
    TemplateHead reference;
    parallel_for(
        0, 2,
        [&](std::size_t part) {
          if (part == 0) {
            build_template();
          } else {
            reference = make_template_skull(template_options);
            read_skull();
          }
        },
        1);
    detect(reference);
    // The file's template is carried by that registration only when its skull is the reference's (a built-in
    // template written by template build --builtin); a skull of its own would need a registration of its own.
    registered_skull_is_fitted =
        reference.skull.positions == head.skull.positions && reference.skull.triangles == head.skull.triangles;
  } else if (landmark_mode == "auto") {
    // Detection needs only the template's skull and its landmarks: it runs while the template's skin, atlas and
    // muscles are built, and the halves are joined after.
    head = make_template_head_beside(template_options, [&](const TemplateHead& skull_part) {
      read_skull();
      detect(skull_part);
    });
    template_s = head.seconds_skin + head.seconds_atlas + head.seconds_skull + head.seconds_landmarks;
  } else {
    parallel_for(
        0, 2, [&](std::size_t part) { part == 0 ? build_template() : read_skull(); }, 1);
  }
  timings.add("template", template_s);
  timings.add("skull", skull_s);
  if (detection) {
    for (const auto& [name, reason] : detection->left_out)
      std::printf("landmark %s left out: %s\n", name.c_str(), reason.c_str());
    timings.add(completion ? "landmark detection and skull completion" : "landmark detection", detection_s);
    timings.add(
        builtin_skull ? "template and landmark detection" : "template, skull and landmark detection (side by side)",
        watch.lap());
  } else {
    timings.add("template and skull (side by side)", watch.lap());
  }
  const LandmarkSet skull_landmarks_in = file_landmarks ? *file_landmarks
                                         : detection    ? detection->landmarks
                                                        : template_skull_landmarks(head);
  const std::string landmark_origin =
      file_landmarks ? "file " + landmark_mode
      : detection    ? "detected: the template's skull landmarks registered onto the skull (similarity, then "
                       "non-rigid) and refined by their definitions in the skull's head frame"
                     : "the template's skull landmarks (placed by their definitions)";
  // The skull's head frame where the landmarks' origin gives it: detected, or the template's own.
  const std::optional<HeadFrame> known_frame = detection                     ? std::optional(detection->frame)
                                               : landmark_mode == "template" ? std::optional(template_head_frame(head))
                                                                             : std::nullopt;

  // 4. The reconstruction: depth vectors, the fit with interpolated landmarks, the guides, the violations.
  ReconstructionOptions options;
  options.fit.interpolated_landmarks = job.interpolated_landmarks;
  if (job.has_guides) options.guides = job.guides;
  nlohmann::json measured_guides = nullptr;
  if (job.measure_guides) {
    const SkullGuideMeasurement m =
        measure_skull_guides(skull.mesh, skull_landmarks_in, known_frame ? &*known_frame : nullptr);
    if (any_guide(m.guides)) options.guides = merge_face_guides(m.guides, job.has_guides ? job.guides : FaceGuides{});
    measured_guides = {{"measured", m.measured},
                       {"missing", m.missing},
                       {"head_frame", m.head_frame},
                       {"values", face_guides_json(m.guides)},
                       {"aperture_width_mm", m.aperture_width_mm},
                       {"spine_length_mm", m.spine_length_mm}};
    std::string line = "guides measured on the skull:";
    for (const std::string& g : m.measured) line += " " + g;
    if (m.measured.empty()) line += " none";
    for (const std::string& why : m.missing) line += "; not " + why;
    std::printf("%s\n", line.c_str());
  }
  // The template carried onto the skull by the registration that found the landmarks (template_carry.hpp), so the
  // warp of eq. 1 sets the tissue depths on a head that already lies on this skull.
  std::optional<TemplateHead> carried;
  if (job.carry_template && detection && registered_skull_is_fitted) {
    carried = carry_template_head(head, detection->registration);
    timings.add("template carried onto the skull", watch.lap());
  }
  const TemplateHead& fitted_head = carried ? *carried : head;
  Reconstruction reconstruction(fitted_head, skull.mesh, skull_landmarks_in, depths, options);
  const ReconstructionResult& result = reconstruction.result();
  const TemplateFitResult& fit = reconstruction.fit();
  const DepthVectors& vectors = result.depth_vectors;
  TriMesh final_skin = result.skin;
  timings.add("reconstruction", watch.lap());

  std::optional<ReconstructionUncertainty> uncertainty;
  if (job.uncertainty_samples > 0) {
    uncertainty =
        reconstruction_uncertainty(reconstruction, job.uncertainty_samples, job.uncertainty_seed.value_or(job.seed));
    final_skin.vertex_fields.scalars["uncertainty"] = uncertainty->vertex_spread_mm;
    timings.add("uncertainty", watch.lap());
  }

  // The evaluation: the CT's real face against the reconstruction over the face region.
  std::optional<FaceEvaluation> evaluation;
  nlohmann::json evaluation_record;
  if (job.evaluate) {
    double skin_iso = 0.0;
    const TriMesh real_skin = real_face_surface(*volume, skull.source, {}, &skin_iso);
    // The frame of the region: detected, the template's (its own landmarks), or from the file's Frankfort landmarks.
    const HeadFrame frame = known_frame ? *known_frame : head_frame_from_skull(skull.mesh, skull_landmarks_in);
    LandmarkSet used("skull");
    for (const DepthVector& v : result.depth_vectors.vectors) used.add({v.bone_landmark, v.bone_mm, v.source, 1.0});
    const FaceRegionOptions region_options;
    const FaceRegion region = face_region(used, frame, region_options);
    evaluation = evaluate_face(real_skin, result.skin, region, skull.field_of_view);
    evaluation_record = evaluation->to_json();
    evaluation_record["real_face"] = {{"source", skull.source},
                                      {"skin_iso", skin_iso},
                                      {"triangles", real_skin.triangle_count()},
                                      {"measured_triangles", evaluation->face.triangle_count()}};
    evaluation_record["region"] = {
        {"definition",
         "in front of the coronal plane through the gonia, below the Frankfort-parallel plane " +
             fmt::format("{:g}", region_options.forehead_mm) +
             " mm above glabella, above the mandibular plane (menton, gonia) lowered by " +
             fmt::format("{:g}", region_options.chin_margin_mm) +
             " mm; exterior skin only (a ray along the normal leaves the head), the scan's cut caps left out"},
        {"frame", detection                     ? "detected head frame"
                  : landmark_mode == "template" ? "template head frame"
                                                : "head frame of the landmark file (Frankfort, midsagittal)"}};
    evaluation_record["method"] =
        "signed distance from each real-face vertex to the closest point of the reconstructed skin (positive: "
        "the real face outside the reconstruction), weighted by a third of its triangles' area";
    evaluation_record["literature_within_2_5mm_percent"] = {54, 77};
    timings.add("evaluation", watch.lap());
  }

  // Expressions (paper section 5): the muscles contracted under the reconstructed skin, over the target skull;
  // each preset becomes a morph target of the head in the GLB.
  std::vector<MorphTarget> expression_targets;
  if (!job.expressions.empty()) {
    expression_targets = expression_morph_targets(result.skin, skull.mesh, result.muscles, job.expressions);
    timings.add("expressions", watch.lap());
  }

  // 5. Landmark sets, maps, pictures: all in memory.
  LandmarkSet skull_set("skull");
  for (const DepthVector& v : vectors.vectors) skull_set.add({v.bone_landmark, v.bone_mm, v.source, v.confidence});
  LandmarkSet skin_set = result.skin_landmarks;
  skin_set.set_name("skin");

  std::shared_ptr<Image> epidermis, normal_map;
  final_skin.material.name = "skin";
  if (job.texture_size > 0 && !head.texture_png.empty()) {
    // A template built from a textured head carries its own map on the atlas; the warp keeps the UVs.
    epidermis = std::make_shared<Image>(decode_png(head.texture_png, job.template_file + " texture"));
    timings.add("skin maps", watch.lap());
  } else if (job.texture_size > 0 && head.skin.has_uvs()) {
    // The maps are baked on the template's rest shape; the warp keeps the UVs, so they follow the face.
    SkinMaps maps = make_skin_maps(head.skin, job.texture_size, job.seed);
    epidermis = std::make_shared<Image>(std::move(maps.epidermis));
    normal_map = std::make_shared<Image>(std::move(maps.normal));
    timings.add("skin maps", watch.lap());
  }
  // "auto": the detected head frame (superior up, the face to the front) where landmarks were detected.
  ViewAxes axes = axes_from_name(job.axes == "auto" ? "lps" : job.axes);
  if (job.axes == "auto" && detection) axes = ViewAxes{detection->frame.axes.col(2), -detection->frame.axes.col(1)};
  std::vector<std::pair<std::string, std::string>> pictures;  // file, PNG bytes
  if (job.picture_size > 0) {
    RenderSettings settings;
    settings.width = settings.height = job.picture_size;
    settings.samples_per_pixel = job.samples;
    settings.seed = job.seed;
    auto skin_ptr = std::make_shared<const TriMesh>(final_skin);
    auto skull_ptr = std::make_shared<const TriMesh>(skull.mesh);
    Scene overlay = skin_over_bone_scene(skin_ptr, skull_ptr, 0.35, axes);
    std::vector<std::pair<Vec3, Vec3>> depth_lines;
    for (const DepthVector& v : vectors.vectors) depth_lines.emplace_back(v.bone_mm, v.skin_mm);
    add_depth_vectors(overlay, depth_lines);
    std::vector<SheetCell> cells;
    for (const auto& [view, caption] : std::vector<std::pair<std::string, std::string>>{
             {"front", "front"}, {"left", "side"}, {"three_quarter", "three-quarter"}}) {
      Image image = render_view(overlay, settings, view, axes);
      pictures.emplace_back("render_" + (view == "left" ? std::string("side") : view) + ".png", encode_png(image));
      cells.push_back({std::move(image), caption});
    }
    Scene face;
    face.environment.up = axes.up;
    SurfaceMaterial material = SurfaceMaterial::skin();
    if (epidermis) {
      material.colour_source = ColourSource::texture;
      material.base_colour = Vec3f(1, 1, 1);
      material.base_texture = epidermis;
      material.normal_map = normal_map;
    }
    face.add(skin_ptr, material, "skin");
    Image textured = render_view(face, settings, "three_quarter", axes);
    pictures.emplace_back("render_textured.png", encode_png(textured));
    cells.push_back({std::move(textured), "reconstructed head"});
    if (uncertainty) {
      // The spread over the reconstructed face, with its scale.
      Scene spread;
      spread.environment.up = axes.up;
      const double top = std::max(uncertainty->max_spread_mm, 1e-3);
      spread.add(skin_ptr, SurfaceMaterial::field("uncertainty", 0.0, top, ColormapName::inferno), "spread");
      ColourBar bar;
      bar.colormap = Colormap{ColormapName::inferno};
      bar.max = top;
      bar.title = "spread";
      bar.unit = "mm";
      Image map = with_colour_bar(render_view(spread, settings, "three_quarter", axes), bar);
      pictures.emplace_back("render_uncertainty.png", encode_png(map));
      cells.push_back({std::move(map), "uncertainty (" + std::to_string(uncertainty->samples) + " samples)"});
    }
    if (evaluation) {
      // The real face coloured by its signed distance from the reconstruction, front and side, with the scale.
      Scene heat;
      heat.environment.up = axes.up;
      const double range = std::max(5.0, std::ceil(evaluation->p90_abs_mm));
      heat.add(std::make_shared<const TriMesh>(evaluation->face),
               SurfaceMaterial::field("distance", -range, range, ColormapName::blue_white_red), "real face");
      ColourBar bar;
      bar.colormap = Colormap{ColormapName::blue_white_red};
      bar.min = -range;
      bar.max = range;
      bar.title = "real - reconstruction";
      bar.unit = "mm";
      std::vector<SheetCell> heat_cells;
      heat_cells.push_back({render_view(heat, settings, "front", axes), "front"});
      heat_cells.push_back({render_view(heat, settings, "left", axes), "side"});
      // The figures are in evaluation.json (a title long enough to hold them would be cut at small sizes).
      Image sheet = make_sheet(heat_cells, 2, "real face vs reconstruction");
      pictures.emplace_back("evaluation.png", encode_png(with_colour_bar(sheet, bar)));
    }
    pictures.emplace_back("reconstruction.png", encode_png(make_sheet(cells, 4, "forensim reconstruct")));
    if (!expression_targets.empty()) {
      // The expressions sheet: the neutral face, then each preset, from the front.
      std::vector<SheetCell> expression_cells;
      SurfaceMaterial skin_material = SurfaceMaterial::skin();
      if (epidermis) {
        skin_material.colour_source = ColourSource::texture;
        skin_material.base_colour = Vec3f(1, 1, 1);
        skin_material.base_texture = epidermis;
        skin_material.normal_map = normal_map;
      }
      auto render_face = [&](std::shared_ptr<const TriMesh> mesh) {
        Scene scene;
        scene.environment.up = axes.up;
        scene.add(std::move(mesh), skin_material, "skin");
        return render_view(scene, settings, "front", axes);
      };
      expression_cells.push_back({render_face(skin_ptr), "neutral"});
      for (const MorphTarget& target : expression_targets) {
        auto posed = std::make_shared<TriMesh>(final_skin);
        for (std::size_t v = 0; v < posed->positions.size(); ++v) posed->positions[v] += target.position_deltas[v];
        expression_cells.push_back({render_face(posed), target.name});
      }
      pictures.emplace_back("expressions.png",
                            encode_png(make_sheet(expression_cells, 4, "forensim reconstruct: expressions")));
    }
    timings.add("renders", watch.lap());
  }

  // 6. Provenance.
  nlohmann::json provenance;
  provenance["template"] = {
      {"name", template_from_file ? job.template_file : "built-in head phantom template"},
      {"source", fitted_head.source},
      {"carried_onto_skull", carried.has_value()},
      {"detail", template_from_file ? "file" : job.template_detail},
      {"landmark_reference", template_from_file && detection ? "built-in template skull (" + job.template_detail + ")"
                                                             : std::string("the template's skull")},
      {"own_texture", !head.texture_png.empty()},
      {"skin_triangles", head.skin.triangle_count()},
      {"landmark_pairs", head.landmarks.size()},
      {"muscles", head.muscles.size()},
      {"uv_atlas", head.skin.has_uvs()}};
  provenance["skull"] = {{"source", skull.source},
                         {"kind", skull.kind.empty() ? "mesh" : skull.kind},
                         {"triangles", skull.mesh.triangle_count()},
                         {"notes", skull.notes}};
  if (skull.iso_value) provenance["skull"]["bone_iso"] = *skull.iso_value;
  if (skull.seed_iso_value) {
    provenance["skull"]["bone_threshold"] = {
        {"method", "half-maximum height (Spoor et al. 1993; Coleman and Colbert 2007)"},
        {"seed_iso", *skull.seed_iso_value},
        {"profiles", skull.threshold_profiles}};
  }
  provenance["table"] = {{"name", table.name},
                         {"origin", table.origin},
                         {"source", table.comments},
                         {"group", depths.group.describe()},
                         {"variant", depths.variant},
                         {"notes", depths.notes},
                         {"build", job.build.empty() ? "as the group" : job.build}};
  if (!build_method.empty()) provenance["table"]["build_method"] = build_method;
  const nlohmann::json record = reconstruction.provenance();
  provenance["landmarks"] = record["landmarks"];
  provenance["landmarks"]["origin"] = landmark_origin;
  if (detection) {
    nlohmann::json details = nlohmann::json::array();
    for (const DetectedLandmark& d : detection->details) {
      details.push_back({{"name", d.name},
                         {"rule", to_string(d.rule)},
                         {"confidence", d.confidence},
                         {"residual_mm", d.residual_mm},
                         {"sharpness", d.sharpness},
                         {"symmetry_error_mm", d.symmetry_error_mm},
                         {"refinement_mm", (d.refined_mm - d.transferred_mm).norm()},
                         {"transferred_mm", {d.transferred_mm.x(), d.transferred_mm.y(), d.transferred_mm.z()}},
                         {"in_view", d.in_view}});
    }
    const SkullRegistration& reg = detection->registration;
    provenance["landmarks"]["detection"] = {{"reference", "template skull"},
                                            {"similarity_scale", reg.similarity.scale},
                                            {"similarity_rms_mm", reg.similarity_rms_mm},
                                            {"non_rigid_rms_mm", reg.rms_mm},
                                            {"head_frame", head_frame_json(detection->frame)},
                                            {"landmarks", details}};
    nlohmann::json left_out = nlohmann::json::array();
    for (const auto& [name, reason] : detection->left_out) left_out.push_back({{"name", name}, {"reason", reason}});
    provenance["landmarks"]["detection"]["left_out"] = left_out;
  }
  provenance["guides"] = guides_record;
  if (job.measure_guides) provenance["guides_measured"] = measured_guides;
  if (options.guides) provenance["guides_adjusted"] = record["guides_adjusted"];
  if (!expression_targets.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const MorphTarget& target : expression_targets) {
      double largest = 0.0;
      for (const Vec3& d : target.position_deltas) largest = std::max(largest, d.norm());
      list.push_back({{"name", target.name}, {"max_displacement_mm", largest}});
    }
    provenance["expressions"] = {
        {"model", "skin-muscle-skull springs with linear and sphincter muscles (paper section 5)"},
        {"morph_targets", list}};
  }
  provenance["seed"] = job.seed;
  const nlohmann::json violations = reconstruction.violations_json();

  // 7. Outputs.
  RunFolder run(out, "reconstruct");
  run.set_job(resolved_job);
  run.set_seed(job.seed);
  GltfScene scene;
  GltfMeshNode head_node;
  head_node.name = "head";
  head_node.mesh = final_skin;
  head_node.morph_targets = expression_targets;
  if (epidermis) {
    head_node.textures.base_color_png = encode_png(*epidermis);
    if (normal_map) head_node.textures.normal_png = encode_png(*normal_map);
  }
  scene.nodes.push_back(std::move(head_node));
  scene.nodes.push_back(skull_gltf_node("skull", skull.mesh));
  write_gltf(run.file("head.glb"), scene);
  run.add_output("head.glb");
  TriMesh obj_skin = final_skin;
  if (epidermis) {
    run.write("head_epidermis.png", encode_png(*epidermis));
    if (normal_map) run.write("head_normal.png", encode_png(*normal_map));
    obj_skin.material.base_color_texture = "head_epidermis.png";
    if (normal_map) obj_skin.material.normal_texture = "head_normal.png";
  }
  write_obj(run.file("head.obj"), obj_skin);
  run.add_output("head.obj");
  run.add_output("head.mtl");
  write_obj(run.file("skull.obj"), skull.mesh);
  run.add_output("skull.obj");
  run.add_output("skull.mtl");
  write_landmarks(run.file("skull_landmarks.mrk.json"), skull_set);
  run.add_output("skull_landmarks.mrk.json");
  write_landmarks(run.file("skin_landmarks.mrk.json"), skin_set);
  run.add_output("skin_landmarks.mrk.json");
  if (uncertainty) {
    nlohmann::json u = {{"samples", uncertainty->samples},
                        {"seed", uncertainty->seed},
                        {"method",
                         "depths drawn from the table's means and SDs; spread = RMS distance of the members' "
                         "vertex positions from their mean, per head.obj vertex"},
                        {"max_spread_mm", uncertainty->max_spread_mm},
                        {"mean_spread_mm", uncertainty->mean_spread_mm},
                        {"vertex_spread_mm", uncertainty->vertex_spread_mm}};
    run.write("uncertainty.json", u.dump());
    // The head with its "uncertainty" vertex field (mm), for ParaView and forensim serve's viewer.
    write_vtu(run.file("head_uncertainty.vtu"), final_skin);
    run.add_output("head_uncertainty.vtu");
    provenance["uncertainty"] = {{"samples", uncertainty->samples}, {"seed", uncertainty->seed}};
  }
  if (evaluation) {
    run.write("evaluation.json", evaluation_record.dump(2));
    // The measured real face with its "distance" vertex field (mm), for ParaView and the viewer.
    write_vtu(run.file("evaluation_face.vtu"), evaluation->face);
    run.add_output("evaluation_face.vtu");
    provenance["evaluation"] = evaluation_record;
  }
  for (const auto& [file, bytes] : pictures) run.write(file, bytes);
  run.write("violations.json", violations.dump(2));
  run.write("provenance.json", provenance.dump(2));
  timings.add("write", watch.lap());
  for (const auto& [stage, seconds] : timings.stages()) run.timings().add(stage, seconds);
  run.facts()["given_pairs"] = fit.given_pair_count;
  run.facts()["interpolated_pairs"] = fit.interpolated.names.size();
  run.facts()["correction_pairs"] = fit.corrections.sources.size();
  run.facts()["violations_before"] = result.violations_given_only.total();
  run.facts()["violations_after"] = result.violations_final.total();
  run.facts()["expressions"] = expression_targets.size();
  if (evaluation) {
    run.facts()["evaluation_mean_abs_mm"] = evaluation->mean_abs_mm;
    run.facts()["evaluation_rms_mm"] = evaluation->rms_mm;
    run.facts()["evaluation_signed_mean_mm"] = evaluation->signed_mean_mm;
    run.facts()["evaluation_within_percent"] = 100.0 * evaluation->within_share;
  }
  run.facts()["seconds_total"] = total.seconds();
  run.write_record();
  return run.facts();
}

namespace {

const RegisterCommand reconstruct_command{
    "reconstruct", [](CLI::App& app) {
      auto* sub = app.add_subcommand("reconstruct", "Rebuild a face from a skull (template head, tissue depths)");
      auto a = std::make_shared<ReconstructArgs>();
      ReconstructJob& j = a->job;
      sub->add_option("-o,--out", a->out, "Output folder")->required();
      sub->add_option("--job", a->job_file, "Job file (JSON); options typed on the command line override it");
      sub->add_option("--skull", j.skull, "Skull mesh file (any format Assimp reads) or volume; default: built-in");
      sub->add_option("--ct", j.ct, "CT volume to take the skull from (bone iso-surface), or 'phantom'");
      sub->add_option("--unit", j.unit, "Unit of a mesh skull: auto, m, cm, mm or in")
          ->check(CLI::IsMember({"auto", "m", "cm", "mm", "in"}));
      sub->add_option("--mesh-scale", j.mesh_scale, "Millimetres per mesh unit (overrides --unit)")
          ->check(CLI::Range(0.0, 1e6));
      sub->add_option("--bone-iso", j.bone_iso, "CT bone iso-value in stored units (default 1150 = 126 HU)");
      sub->add_option("--bone-edge", j.bone_edge,
                      "CT bone surface: half-maximum (default without --bone-iso: the 126 HU surface moved to "
                      "the half-maximum height measured across it, thin bone to the plate model's edge) or iso (at "
                      "--bone-iso; the default when it is given)")
          ->check(CLI::IsMember({"iso", "half-maximum"}));
      sub->add_option("--landmarks", j.landmarks,
                      "Skull landmarks: .mrk.json or .csv file, 'template' (built-in skull's own) or 'auto' (detected; "
                      "the default for other skulls)");
      sub->add_option("--table", j.table, "Tissue-depth table: ttable_2023, rhine_1983 or a CSV file");
      sub->add_option("--sex", j.sex, "Group of the table: female, male or pooled")
          ->check(CLI::IsMember({"female", "male", "pooled"}));
      sub->add_option("--population", j.population, "Population group of the table");
      sub->add_option("--build", j.build, "slender, normal or obese (table groups or mean -/+ SD)")
          ->check(CLI::IsMember({"slender", "normal", "obese"}));
      sub->add_option("--build-sd", j.build_sd, "SDs of the build variants when the table has no build groups")
          ->check(CLI::Range(0.1, 3.0));
      sub->add_option("--guides", a->guides_file, "Nose and mouth guide values (JSON, FaceGuides fields)");
      sub->add_flag("--no-interpolated", a->no_interpolated,
                    "Leave out the interpolated cranium and mandible landmarks");
      sub->add_flag("--no-carry", a->no_carry,
                    "With automatic landmarks, warp the template as it is (the paper's fit) instead of first "
                    "carrying it onto the skull by the registration that found them");
      sub->add_flag("--measure-guides", a->measure_guides,
                    "Measure the nose and mouth guides on the skull (aperture, nasal spine, mouth corners); "
                    "--guides values override them");
      sub->add_flag("--evaluate", a->evaluate,
                    "Measure the CT's real face (skin iso-surface) against the reconstruction over the face region "
                    "(forehead to chin, ear to ear): evaluation.json, evaluation.png");
      sub->add_option("--template", j.template_file,
                      "Template file made by forensim template build (default: the built-in template)");
      sub->add_option(
             "--template-detail", j.template_detail,
             "Template head: full or coarse (quicker); with --template, the skull the landmarks are found with")
          ->check(CLI::IsMember({"full", "coarse"}));
      sub->add_option("--axes", j.axes,
                      "Frame of the skull for the pictures: auto (default: the detected head frame with "
                      "--landmarks auto, else lps), lps or yup")
          ->check(CLI::IsMember({"lps", "yup", "auto"}));
      sub->add_option("--seed", j.seed, "Seed of the procedural skin maps");
      sub->add_option("--texture-size", j.texture_size, "Skin map resolution (0 = none)")->check(CLI::Range(0, 8192));
      sub->add_option("--picture-size", j.picture_size, "Pixels per rendered view (0 = no renders)")
          ->check(CLI::Range(0, 4096));
      sub->add_option("--samples", j.samples, "Samples per pixel of the renders")->check(CLI::Range(1, 256));
      sub->add_option("--uncertainty", j.uncertainty_samples,
                      "Members of the uncertainty ensemble (depths drawn from the table's SDs; 0 = none)")
          ->check(CLI::Range(0, 1000));
      sub->add_option("--expressions", a->expressions,
                      "Expression presets as morph targets, comma-separated (neutral, smile, frown, worried, "
                      "surprise), or 'none'; default smile,frown,surprise");
      return [a, sub]() { return run_reconstruct(*a, *sub); };
    }};

}  // namespace
}  // namespace forensim::cli
