#include "reconstruct/reconstruct_inputs.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/face_expression.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/skull_guides.hpp"
#include "craniofacial/template_carry.hpp"
#include "craniofacial/template_file.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "mesh_io/mesh_import.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "volume/volume_reader.hpp"

namespace forensim {
namespace {

/// The table and the job's group of it (the build variant when the job names one).
void select_depths(const ReconstructJob& job, ReconstructInputs& in) {
  in.table = tissue_depth_table(reconstruct_table_name(job.table));
  const TissueDepthQuery query{job.sex, job.population, ""};
  if (job.build.empty()) {
    in.depths = select_tissue_depths(in.table, query);
    return;
  }
  const BuildVariants variants = build_variants(in.table, query, job.build_sd);
  in.depths = variants.of(job.build);
  in.build_method = variants.method;
}

/// Expression names: each a preset (the closest one named otherwise), none twice.
void check_expressions(const std::vector<std::string>& expressions) {
  for (std::size_t i = 0; i < expressions.size(); ++i) {
    static_cast<void>(expression_preset(expressions[i]));
    for (std::size_t k = 0; k < i; ++k)
      if (expressions[k] == expressions[i]) throw InputError("expressions", expressions[i], "listed twice");
  }
}

/// The skull landmarks' origin in words, for the provenance.
std::string landmark_origin(const ReconstructInputs& in, bool from_file) {
  if (from_file) return "file " + in.landmark_mode;
  if (in.detection) {
    return "detected: the template's skull landmarks registered onto the skull (similarity, then non-rigid) and "
           "refined by their definitions in the skull's head frame";
  }
  return "the template's skull landmarks (placed by their definitions)";
}

/// The nose and mouth guides measured on the skull (skull_guides.hpp), the job's own values overriding them.
void measure_guides(const ReconstructJob& job, ReconstructInputs& in) {
  const SkullGuideMeasurement m =
      measure_skull_guides(in.skull.mesh, in.landmarks, in.known_frame ? &*in.known_frame : nullptr);
  if (any_guide(m.guides)) in.options.guides = merge_face_guides(m.guides, job.has_guides ? job.guides : FaceGuides{});
  in.measured_guides = {{"measured", m.measured},
                        {"missing", m.missing},
                        {"head_frame", m.head_frame},
                        {"values", face_guides_json(m.guides)},
                        {"aperture_width_mm", m.aperture_width_mm},
                        {"spine_length_mm", m.spine_length_mm}};
  std::string line = "guides measured on the skull:";
  for (const std::string& g : m.measured) line += " " + g;
  if (m.measured.empty()) line += " none";
  for (const std::string& why : m.missing) line += "; not " + why;
  in.messages.push_back(line);
}

/// Which skull and which landmarks a job asks for.
struct LandmarkChoice {
  bool builtin_skull = false;  ///< the template's own skull
  bool phantom_ct = false;     ///< the built-in CT of the head phantom
  bool from_file = false;      ///< the landmarks are read from a file (read here)
};

/// The landmark mode: a file, the template's own (for skulls in the template's frame: the built-in skull and the
/// CT phantom, their default), or detected on the skull with the template's skull as the reference (the default
/// for any other skull). Refuses the template's landmarks on another skull and an evaluation without a CT; reads
/// a landmark file.
LandmarkChoice choose_landmarks(const ReconstructJob& job, ReconstructInputs& in) {
  LandmarkChoice c;
  c.builtin_skull = job.ct.empty() && job.skull == "builtin";
  c.phantom_ct = job.ct == "phantom";
  in.landmark_mode = job.landmarks;
  if (in.landmark_mode.empty()) in.landmark_mode = c.builtin_skull || c.phantom_ct ? "template" : "auto";
  if (in.landmark_mode == "template" && !c.builtin_skull && !c.phantom_ct) {
    throw InputError("--landmarks", "template",
                     "only the built-in skull and the CT phantom carry the template's landmarks; give a .mrk.json or "
                     "CSV file, or 'auto' to detect them");
  }
  if (job.evaluate && (c.builtin_skull || (job.ct.empty() && !is_volume_path(job.skull)))) {
    throw InputError("--evaluate", c.builtin_skull ? "built-in skull" : job.skull,
                     "the evaluation needs a CT that holds the face (its skin); a mesh skull has none");
  }
  c.from_file = in.landmark_mode != "template" && in.landmark_mode != "auto";
  if (c.from_file) in.landmarks = read_landmarks(in.landmark_mode);
  return c;
}

/// A skull file read before the template build starts beside the skull's extraction, so a bad file is an error
/// in a tenth of a second, not after the template: a CT into in.volume, a mesh returned.
std::optional<ImportedMesh> read_skull_file(const std::string& path, const SkullInputOptions& options,
                                            ReconstructInputs& in) {
  if (is_volume_path(path)) {
    if (!std::filesystem::exists(path)) throw IoError(path, "does not exist");
    in.volume = read_volume(path);
    return std::nullopt;
  }
  return import_mesh_with_textures(path, options.mesh_units);
}

/// Automatic landmarks: the template's skull registered onto the skull, its landmarks refined there; landmarks the
/// scan did not see lie on the registered template, whose missing part completes the skull. Returns the seconds.
double detect_landmarks(const TemplateHead& reference, ReconstructInputs& in) {
  Stopwatch part;
  ScanLandmarkDetection found = detect_scan_landmarks(reference, in.skull.mesh, in.skull.field_of_view);
  in.detection = std::move(found.detection);
  in.completion = std::move(found.completion);
  const double seconds = part.lap();
  if (in.completion) {
    in.skull.mesh = in.completion->mesh;
    in.skull.notes.push_back(fmt::format(
        "{} landmarks lie outside the scan: completed with the registered template skull ({} triangles, {} cap "
        "triangles of the cut dropped)",
        found.unseen, in.completion->reference_triangles, in.completion->cap_triangles));
  }
  return seconds;
}

/// The overlapping stages' own times, then the wall time of them together; the landmarks left out as messages.
void record_stage_times(bool builtin_skull, double template_s, double skull_s, double detection_s, Stopwatch& watch,
                        ReconstructInputs& in) {
  in.timings.add("template", template_s);
  in.timings.add("skull", skull_s);
  if (!in.detection) {
    in.timings.add("template and skull (side by side)", watch.lap());
    return;
  }
  for (const auto& [name, reason] : in.detection->left_out)
    in.messages.push_back(fmt::format("landmark {} left out: {}", name, reason));
  in.timings.add(in.completion ? "landmark detection and skull completion" : "landmark detection", detection_s);
  in.timings.add(
      builtin_skull ? "template and landmark detection" : "template, skull and landmark detection (side by side)",
      watch.lap());
}

/// After the skull, template and detection: the warp's landmarks, their origin and head frame, the fit options
/// and guides, and the template carried onto the skull by the registration that found the landmarks
/// (template_carry.hpp), so the warp of eq. 1 sets the tissue depths on a head that already lies on this skull.
void finish_inputs(const ReconstructJob& job, bool from_file, bool registered_skull_is_fitted, Stopwatch& watch,
                   ReconstructInputs& in) {
  if (in.detection) {
    in.landmarks = in.detection->landmarks;
  } else if (!from_file) {
    in.landmarks = template_skull_landmarks(*in.head);
  }
  in.landmark_origin = landmark_origin(in, from_file);
  // The skull's head frame where the landmarks' origin gives it: detected, or the template's own.
  if (in.detection) {
    in.known_frame = in.detection->frame;
  } else if (in.landmark_mode == "template") {
    in.known_frame = template_head_frame(*in.head);
  }
  in.options.fit.interpolated_landmarks = job.interpolated_landmarks;
  if (job.has_guides) in.options.guides = job.guides;
  if (job.measure_guides) measure_guides(job, in);
  if (job.carry_template && in.detection && registered_skull_is_fitted) {
    in.fitted = std::make_shared<const TemplateHead>(carry_template_head(*in.head, in.detection->registration));
    in.carried = true;
    in.timings.add("template carried onto the skull", watch.lap());
  } else {
    in.fitted = in.head;
  }
}

}  // namespace

ReconstructInputs prepare_reconstruction(const ReconstructJob& job, std::shared_ptr<const TemplateHead> prebuilt) {
  if (prebuilt && !job.template_file.empty())
    throw std::invalid_argument("prepare_reconstruction: a prebuilt template head with a template file");
  Stopwatch watch;
  ReconstructInputs in;
  // The table and depths, and the expression names (cheap, checked first).
  select_depths(job, in);
  check_expressions(job.expressions);

  const LandmarkChoice choice = choose_landmarks(job, in);
  const bool builtin_skull = choice.builtin_skull, phantom_ct = choice.phantom_ct;
  const bool auto_landmarks = in.landmark_mode == "auto";
  in.timings.add("inputs", watch.lap());

  const TemplateHeadOptions template_options = template_head_options(job.template_detail);
  const SkullInputOptions skull_options = skull_input_options(job);
  const std::string skull_path = job.ct.empty() ? job.skull : job.ct;
  Stopwatch skull_read;
  std::optional<ImportedMesh> skull_file =
      builtin_skull || phantom_ct ? std::nullopt : read_skull_file(skull_path, skull_options, in);

  // The template and the skull are independent: a CT's skull is read and extracted while the template is built
  // (each stage's own time is recorded; they overlap).
  double template_s = 0.0, skull_s = skull_read.seconds(), detection_s = 0.0;
  in.template_from_file = !job.template_file.empty();
  TemplateHead built;
  const auto build_template = [&] {
    if (prebuilt) return;
    Stopwatch part;
    built = in.template_from_file ? read_template_head(job.template_file) : make_template_head(template_options);
    template_s = part.seconds();
  };
  const auto read_skull = [&] {
    Stopwatch part;
    if (phantom_ct) {
      in.volume = make_ct_head_phantom();
      in.skull = skull_from_volume(*in.volume, "built-in CT head phantom", skull_options);
    } else if (is_volume_path(skull_path)) {
      in.skull = skull_from_volume(*in.volume, skull_path, skull_options);
    } else {
      in.skull = skull_from_mesh(std::move(skull_file->mesh), skull_path, skull_options);
      in.skull.mm_per_unit = skull_file->mm_per_unit;
    }
    skull_s += part.seconds();
  };
  const auto detect = [&](const TemplateHead& reference) { detection_s = detect_landmarks(reference, in); };
  const auto template_head = [&]() -> const TemplateHead& { return prebuilt ? *prebuilt : built; };
  bool registered_skull_is_fitted = true;  // the detection's registration maps the fitted template's skull
  if (builtin_skull) {
    build_template();
    in.skull.mesh = template_head().skull;
    in.skull.source = "built-in template skull (head phantom)";
    in.skull.kind = "builtin";
    if (auto_landmarks) detect(template_head());
  } else if (prebuilt) {
    read_skull();
    if (auto_landmarks) detect(*prebuilt);
  } else if (auto_landmarks && in.template_from_file) {
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
        reference.skull.positions == built.skull.positions && reference.skull.triangles == built.skull.triangles;
  } else if (auto_landmarks) {
    // Detection needs only the template's skull and its landmarks: it runs while the template's skin, atlas and
    // muscles are built, and the halves are joined after.
    built = make_template_head_beside(template_options, [&](const TemplateHead& skull_part) {
      read_skull();
      detect(skull_part);
    });
    template_s = built.seconds_skin + built.seconds_atlas + built.seconds_skull + built.seconds_landmarks;
  } else {
    parallel_for(
        0, 2, [&](std::size_t part) { part == 0 ? build_template() : read_skull(); }, 1);
  }
  in.head = prebuilt ? std::move(prebuilt) : std::make_shared<const TemplateHead>(std::move(built));
  record_stage_times(builtin_skull, template_s, skull_s, detection_s, watch, in);
  finish_inputs(job, choice.from_file, registered_skull_is_fitted, watch, in);
  return in;
}

}  // namespace forensim
