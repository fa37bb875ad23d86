#include "reconstruct/reconstruct_job.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "craniofacial/face_expression.hpp"

namespace forensim {
namespace {

std::string resolve_path(const std::string& value, const std::filesystem::path& base) {
  if (value.empty() || base.empty()) return value;
  const std::filesystem::path p(value);
  return p.is_absolute() ? value : (base / p).string();
}

// A path key: resolved against the job file's folder when the job gives it (command-line values stay as typed).
std::string path_value(const JobNode& root, const std::string& key, const std::string& fallback,
                       const std::filesystem::path& base, const std::vector<std::string>& words) {
  const bool given = root.has(key);
  const std::string value = root.get<std::string>(key, fallback);
  if (!given) return value;
  for (const auto& w : words)
    if (value == w) return value;
  return resolve_path(value, base);
}

}  // namespace

ReconstructJob read_reconstruct_job(const JobNode& root, const ReconstructJob& defaults,
                                    const std::filesystem::path& base) {
  ReconstructJob j = defaults;
  root.get_integer("version", 1, 1, 1);
  j.skull = path_value(root, "skull", defaults.skull, base, {"builtin"});
  j.ct = path_value(root, "ct", defaults.ct, base, {"phantom"});
  j.unit = root.get_choice("unit", defaults.unit, {"auto", "m", "cm", "mm", "in"});
  j.mesh_scale = root.get_number("mesh_scale", defaults.mesh_scale, 0.0, 1e6);
  if (root.has("bone_iso")) {
    j.bone_iso = root.get_number("bone_iso", 0.0, -1e6, 1e6);
  }
  j.bone_edge = root.get_choice("bone_edge", defaults.bone_edge, {"", "iso", "half-maximum"});
  j.landmarks = path_value(root, "landmarks", defaults.landmarks, base, {"template", "auto"});
  j.table = path_value(root, "table", defaults.table, base, {"ttable_2023", "rhine_1983"});
  j.sex = root.get_choice("sex", defaults.sex, {"", "female", "male", "pooled"});
  j.population = root.get<std::string>("population", defaults.population);
  j.build = root.get_choice("build", defaults.build, {"", "slender", "normal", "obese"});
  j.build_sd = root.get_number("build_sd", defaults.build_sd, 0.1, 3.0);
  if (root.has("guides")) {
    j.guides = read_face_guides(root.child("guides"));
    j.has_guides = any_guide(j.guides);
  }
  j.interpolated_landmarks = root.get<bool>("interpolated_landmarks", defaults.interpolated_landmarks);
  j.carry_template = root.get<bool>("carry_template", defaults.carry_template);
  j.evaluate = root.get<bool>("evaluate", defaults.evaluate);
  j.measure_guides = root.get<bool>("measure_guides", defaults.measure_guides);
  j.template_detail = root.get_choice("template_detail", defaults.template_detail, {"full", "coarse"});
  j.template_file = path_value(root, "template", defaults.template_file, base, {});
  j.axes = root.get_choice("axes", defaults.axes, {"lps", "yup", "auto"});
  j.seed = static_cast<std::uint64_t>(
      root.get_integer("seed", static_cast<long long>(defaults.seed), 0, std::numeric_limits<long long>::max()));
  j.texture_size = static_cast<int>(root.get_integer("texture_size", defaults.texture_size, 0, 8192));
  if (j.texture_size != 0 && j.texture_size < 16) root.fail("texture_size", "must be 0 (no maps) or at least 16");
  j.picture_size = static_cast<int>(root.get_integer("picture_size", defaults.picture_size, 0, 4096));
  j.samples = static_cast<int>(root.get_integer("samples", defaults.samples, 1, 256));
  if (root.has("uncertainty")) {
    const JobNode u = root.child("uncertainty");
    j.uncertainty_samples = static_cast<int>(u.get_integer("samples", 16, 2, 1000));
    if (u.has("seed")) {
      j.uncertainty_seed =
          static_cast<std::uint64_t>(u.get_integer("seed", 0, 0, std::numeric_limits<long long>::max()));
    }
  }
  if (root.has("expressions")) {
    j.expressions = root.get<std::vector<std::string>>("expressions", defaults.expressions);
    const std::vector<std::string> presets = expression_preset_names();
    for (std::size_t i = 0; i < j.expressions.size(); ++i) {
      const std::string& name = j.expressions[i];
      if (std::find(presets.begin(), presets.end(), name) == presets.end()) {
        std::string known;
        for (const auto& p : presets) known += (known.empty() ? "" : ", ") + p;
        root.fail("expressions", "unknown expression '" + name + "' (known: " + known + ")");
      }
      if (std::find(j.expressions.begin(), j.expressions.begin() + static_cast<std::ptrdiff_t>(i), name) !=
          j.expressions.begin() + static_cast<std::ptrdiff_t>(i))
        root.fail("expressions", "'" + name + "' is listed twice");
    }
  }
  return j;
}

std::string bone_edge_of(const ReconstructJob& job) {
  if (!job.bone_edge.empty()) return job.bone_edge;
  return job.bone_iso ? "iso" : "half-maximum";
}

SkullInputOptions skull_input_options(const ReconstructJob& job) {
  SkullInputOptions options;
  options.mesh_units.unit = job.unit;
  options.mesh_units.scale = job.mesh_scale;
  options.bone_iso_value = job.bone_iso;
  options.half_maximum_height = bone_edge_of(job) == "half-maximum";
  if (job.bone_iso && options.half_maximum_height) {
    throw InputError("--bone-edge", "half-maximum", "measures its own threshold: give it without --bone-iso");
  }
  return options;
}

std::string reconstruct_table_name(const std::string& table) {
  return table == "rhine_1983" ? "rhine_1983_sw_native_american_female_normal" : table;
}

nlohmann::json reconstruct_job_record(const ReconstructJob& job, nlohmann::json resolved) {
  resolved["version"] = 1;
  resolved["skull"] = job.skull;
  resolved["ct"] = job.ct;
  resolved["unit"] = job.unit;
  resolved["mesh_scale"] = job.mesh_scale;
  if (job.bone_iso) resolved["bone_iso"] = *job.bone_iso;
  resolved["bone_edge"] = bone_edge_of(job);
  resolved["landmarks"] = job.landmarks;
  resolved["table"] = job.table;
  resolved["sex"] = job.sex;
  resolved["population"] = job.population;
  resolved["build"] = job.build;
  resolved["build_sd"] = job.build_sd;
  resolved["interpolated_landmarks"] = job.interpolated_landmarks;
  resolved["carry_template"] = job.carry_template;
  resolved["evaluate"] = job.evaluate;
  resolved["measure_guides"] = job.measure_guides;
  resolved["template_detail"] = job.template_detail;
  if (!job.template_file.empty()) resolved["template"] = job.template_file;
  resolved["axes"] = job.axes;
  resolved["seed"] = job.seed;
  resolved["texture_size"] = job.texture_size;
  resolved["picture_size"] = job.picture_size;
  resolved["samples"] = job.samples;
  if (job.uncertainty_samples > 0) {
    resolved["uncertainty"]["samples"] = job.uncertainty_samples;
    if (job.uncertainty_seed) resolved["uncertainty"]["seed"] = *job.uncertainty_seed;
  } else {
    resolved.erase("uncertainty");
  }
  resolved["expressions"] = job.expressions;
  return resolved;
}

}  // namespace forensim
