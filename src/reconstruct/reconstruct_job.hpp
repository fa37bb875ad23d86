#pragma once
/// The description of a craniofacial reconstruction (`forensim reconstruct`, the demo, the skull editor's
/// sessions: reconstruct/reconstruct_face.hpp runs it), read from a job file (JSON, version 1) or from the
/// command line through the one job loader (core/job.hpp), so a misspelt key is an error naming it.
///
/// Job keys (all optional):
///   version          1
///   skull            "builtin" (the template's own skull), a mesh file, or a CT volume (is_volume_path)
///   ct               a CT volume, or "phantom" (the built-in CT of the head phantom); replaces `skull`
///   unit, mesh_scale units of a mesh skull (auto, m, cm, mm, in; millimetres per unit)
///   bone_iso         CT bone iso-value (stored values; default 1150, i.e. 126 HU stored as HU + 1024)
///   bone_edge        "half-maximum" (default without bone_iso: the 126 HU surface moved to the half-maximum
///                    height threshold measured across it, thin bone to the plate model's edge;
///                    volume/half_maximum_height) or "iso" (default with bone_iso: the bone surface at bone_iso)
///   landmarks        skull landmarks: a .mrk.json or .csv file, "template" (the template's skull landmarks,
///                    for the built-in skull and the CT phantom) or "auto" (detected: the template's skull
///                    registered onto the skull, each landmark refined by its definition, with a confidence)
///   table            "ttable_2023" (default), "rhine_1983" or a CSV table file
///   sex, population  group of the table ("" = any; pooled values stand in, with a note)
///   build            "" (the group's own values), slender, normal or obese (the table's build groups, or
///                    mean -/+ build_sd SDs)
///   build_sd         k of the build variants (default 1)
///   guides           nose and mouth guide values (face_guides.hpp), an object with the FaceGuides fields
///   interpolated_landmarks  true (default): add cranium and mandible pairs (paper Figure 6b)
///   carry_template   true (default): with automatic landmarks, the template head is first carried onto the skull
///                    by the registration of its skull that found them (template_carry.hpp), then warped by its
///                    landmark pairs; false: the template as it is, warped by its pairs alone (the paper's fit).
///                    A template file is carried only when its skull is the built-in one the landmarks were found
///                    with (template build --builtin)
///   template_detail  "full" (default) or "coarse" (a quicker, coarser template)
///   template         a template file (forensim template build; template_file.hpp) instead of the built-in
///                    template: its skin, skull, landmark pairs, muscles and texture (automatic landmarks are
///                    still found with the built-in template's skull at template_detail)
///   axes             "auto" (default: the detected head frame with automatic landmarks, else lps), "lps" or
///                    "yup": the skull's frame, for the pictures (a CT stored feet-up or tilted comes out upright
///                    with auto)
///   seed             seed of the procedural skin maps
///   texture_size     skin map resolution (0 = no maps)
///   picture_size, samples  renders (picture_size 0 = no renders)
///   uncertainty      {"samples": N, "seed": S}: an ensemble of N reconstructions (2..1000) with depths drawn from
///                    the table's SDs (seed S, default the job's seed); writes the per-vertex spread
///                    (uncertainty.json, head_uncertainty.vtu with the vertex field "uncertainty" in mm,
///                    render_uncertainty.png)
///   expressions      expression presets written as the GLB's morph targets (shape keys) and drawn in
///                    expressions.png: a list of names from neutral, smile, frown, worried, surprise (default
///                    ["smile", "frown", "surprise"]; [] for none)
///   evaluate         false (default); true: the CT's real face (its skin iso-surface) measured against the
///                    reconstruction over the face region (face_evaluation.hpp): evaluation.json, evaluation.png,
///                    evaluation_face.vtu; the skull must come from a CT that holds the face
///   measure_guides   false (default); true: the nose and mouth guides measured on the skull (skull_guides.hpp:
///                    nasal aperture, nasal spine, mouth corners), the "guides" values given overriding them
/// Relative paths in a job file are taken from the job file's folder.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/job.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "craniofacial/skull_input.hpp"

namespace forensim {

struct ReconstructJob {
  std::string skull = "builtin";
  std::string ct;
  std::string unit = "auto";
  double mesh_scale = 0.0;
  std::optional<double> bone_iso;
  std::string bone_edge;  ///< empty: "iso" when bone_iso is given, else "half-maximum" (bone_edge_of)
  std::string landmarks;  ///< empty: "template" for the built-in skull and CT phantom, else "auto"
  std::string table = "ttable_2023";
  std::string sex, population, build;
  double build_sd = 1.0;
  FaceGuides guides;
  bool has_guides = false;
  bool interpolated_landmarks = true;
  bool carry_template = true;
  std::string template_detail = "full";
  std::string template_file;  ///< empty: the built-in template at template_detail
  std::string axes = "auto";
  std::uint64_t seed = 1;
  int texture_size = 1024;
  int picture_size = 512;
  int samples = 4;
  int uncertainty_samples = 0;  ///< 0: no ensemble
  std::optional<std::uint64_t> uncertainty_seed;
  std::vector<std::string> expressions = {"smile", "frown", "surprise"};
  bool evaluate = false;
  bool measure_guides = false;
};

/// Reads a reconstruction job; `defaults` supplies every value the job leaves out (the command line's).
/// `base` is the folder relative paths are resolved against (empty: as given). Throws JobError.
ReconstructJob read_reconstruct_job(const JobNode& root, const ReconstructJob& defaults,
                                    const std::filesystem::path& base);

/// The CT bone edge the job asks for: its bone_edge, or when that is empty "iso" with a bone_iso and
/// "half-maximum" without.
std::string bone_edge_of(const ReconstructJob& job);

/// How the job reads its skull: mesh units, bone iso-value and bone edge (bone_edge_of). The one place the
/// command's defaults become SkullInputOptions (forensim bench reconstruct times the same). Throws InputError
/// naming --bone-edge for half-maximum with a bone_iso (the edge measures its own threshold).
SkullInputOptions skull_input_options(const ReconstructJob& job);

/// The job as it runs, for run.json: `resolved` (the job file's values as read, defaults included) with every
/// key replaced by `job`'s final value, so options and flags typed on the command line (--evaluate,
/// --measure-guides, --no-interpolated, --expressions, ...) are recorded and the record read back by
/// read_reconstruct_job gives the same job. The guides stay as read (provenance.json records a --guides file).
nlohmann::json reconstruct_job_record(const ReconstructJob& job, nlohmann::json resolved);

/// The built-in table or CSV file a job's `table` names: "rhine_1983" is its south-west Native American
/// female column of normal build (the table file's own name), any other value is given to tissue_depth_table.
std::string reconstruct_table_name(const std::string& table);

}  // namespace forensim
