// forensim reconstruct: rebuilds a face from a skull (Kähler, Haber and Seidel 2003). Reads the options and a
// job file into a ReconstructJob (reconstruct/reconstruct_job.hpp), runs it (reconstruct_outputs.hpp: the
// library's reconstruct_face, then the run folder) and prints its figures.

#include <cstdio>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/job.hpp"
#include "craniofacial/face_expression.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "reconstruct/reconstruct_job.hpp"
#include "reconstruct_outputs.hpp"

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
