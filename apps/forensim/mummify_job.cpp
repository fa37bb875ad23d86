// The mummify job loader (shared by the CLI and the server) and the server's "mummify" job kind.

#include "mummify_job.hpp"

#include "core/atomic_file.hpp"
#include "desiccation/material_laws.hpp"
#include "server/api_error.hpp"
#include "server/served_path.hpp"

namespace forensim::cli {
namespace {

/// The "skin" object: livor mortis start state and shading (section 8.3).
SkinShadingJob load_skin_job(const MummifyArgs& a, const JobNode& node) {
  SkinShadingJob skin;
  skin.gravity_given = a.given("--gravity") || node.has("gravity");
  if (skin.gravity_given) {
    const std::vector<double> g = a.given("--gravity") ? a.gravity : node.require<std::vector<double>>("gravity");
    if (g.size() != 3) node.fail("gravity", "needs three numbers [x, y, z]");
    skin.gravity = Vec3(g[0], g[1], g[2]);
    if (!skin.gravity.allFinite() || skin.gravity.norm() < 1e-12)
      node.fail("gravity", "must be a finite, non-zero vector");
    skin.gravity.normalize();
  }
  skin.contact_distance_mm =
      a.given("--contact-mm") ? a.contact_mm : node.get_number("contact_distance_mm", a.contact_mm, -1.0, 1000.0);
  skin.map_resolution =
      static_cast<int>(a.given("--map-size") ? a.map_size : node.get_integer("map_resolution", a.map_size, 0, 8192));
  if (skin.map_resolution != 0 && skin.map_resolution < 16) node.fail("map_resolution", "must be 0 (no maps) or >= 16");
  LivorSettings& l = skin.livor;
  l.blood_fill = node.get_number("blood_fill", l.blood_fill, 0.001, 1.0);
  l.residual_fill = node.get_number("residual_fill", l.residual_fill, 0.0, 0.999);
  if (l.residual_fill >= l.blood_fill) node.fail("residual_fill", "must be below blood_fill");
  l.transition_mm = node.get_number("transition_mm", l.transition_mm, 0.0, 1e4);
  l.contact_capacity = node.get_number("contact_capacity", l.contact_capacity, 0.0, 1.0);
  l.oxygen = node.get_number("oxygen", l.oxygen, 0.0, 1.0);
  SkinShadingSettings& s = skin.shading;
  s.drying_boost = node.get_number("drying_boost", s.drying_boost, 0.0, 4.0);
  s.oxygen_decay_hours = node.get_number("oxygen_decay_hours", s.oxygen_decay_hours, 0.01, 1e5);
  return skin;
}

/// The "skin" object's motion keys: the position-based skin (sections 8.1 and 8.2, eqs. 32 to 35).
SkinMotionJob load_skin_motion_job(const MummifyArgs& a, const JobNode& node) {
  SkinMotionJob motion;
  motion.pbd = node.get<bool>("pbd", motion.pbd);
  motion.substeps = static_cast<int>(node.get_integer("substeps", motion.substeps, 1, 1000));
  SkinSettings& s = motion.settings;
  s.iterations = static_cast<int>(node.get_integer("iterations", s.iterations, 1, 200));
  s.bending_interval = static_cast<int>(node.get_integer("bending_interval", s.bending_interval, 1, 200));
  s.skin_shrinkage = node.get_number("skin_shrinkage", s.skin_shrinkage, 0.0, 0.9);
  const JobNode wrinkle = node.child("wrinkle");
  const bool numbers = wrinkle.has("r_max_relative") || wrinkle.has("damping");
  if (numbers && wrinkle.has("set"))
    wrinkle.fail("set", "give either \"set\" (0, 1 or 2: Figure 8) or \"r_max_relative\" and \"damping\", not both");
  if (!numbers) {
    motion.wrinkle_set = static_cast<int>(wrinkle.get_integer("set", motion.wrinkle_set, 0, 2));
  } else {
    motion.wrinkle_set = -1;
    const WrinkleControls base = WrinkleControls::figure8(1);
    s.wrinkle.r_max_relative = wrinkle.get_number("r_max_relative", base.r_max_relative, 0.0, 0.1);
    s.wrinkle.damping = wrinkle.get_number("damping", base.damping, 0.0, 1.0);
  }
  if (a.given("--wrinkle-set")) motion.wrinkle_set = a.wrinkle_set;  // the command line wins
  if (motion.wrinkle_set >= 0) s.wrinkle = WrinkleControls::figure8(motion.wrinkle_set);
  const JobNode slip = node.child("slippage");
  s.slippage.initial_stiffness = slip.get_number("stiffness", s.slippage.initial_stiffness, 0.0, 1.0);
  s.slippage.decrease_below = slip.get_number("decrease_below", s.slippage.decrease_below, 0.0, 1.0);
  s.slippage.zero_below = slip.get_number("zero_below", s.slippage.zero_below, 0.0, 1.0);
  if (s.slippage.zero_below > s.slippage.decrease_below)
    slip.fail("zero_below", "must not exceed decrease_below (tau_n <= tau_d, eq. 35)");
  return motion;
}

}  // namespace

MummifyJob read_mummify_job(const JobNode& root, const MummifyArgs& a) {
  MummifyJob job;
  root.get_integer("version", 1, 1, 1);
  JobNode body = root.child("body");
  job.phantom = a.given("--phantom") ? a.phantom : body.get_choice("phantom", a.phantom, {"arm", "head"});
  job.size = a.given("--size") ? a.size : body.get_choice("size", a.size, {"small", "paper", "fine"});
  job.model = a.given("--model") ? a.model : body.get<std::string>("model", a.model);
  job.days = a.given("--days") ? a.days : root.get_number("days", a.days, 0.01, 3650.0);
  job.frames = a.given("--frames") ? a.frames : static_cast<int>(root.get_integer("frames", a.frames, 1, 1000));
  job.step_hours = a.given("--step-hours") ? a.step_hours : root.get_number("step_hours", a.step_hours, 0.01, 240.0);
  JobNode env = root.child("environment");
  DryingEnvironment& e = job.settings.environment;
  e.air_temperature_c =
      a.given("--temperature") ? a.temperature : env.get_number("temperature_c", a.temperature, -40, 80);
  e.relative_humidity =
      0.01 * (a.given("--humidity") ? a.humidity : env.get_number("humidity_percent", a.humidity, 0.0, 99.0));
  e.air_speed_m_per_s = a.given("--wind") ? a.wind : env.get_number("wind_m_per_s", a.wind, 0.0, 50.0);
  e.body_diameter_m = env.get_number("body_diameter_m", e.body_diameter_m, 0.005, 2.0);
  e.skin_cover = env.get_number("skin_cover", e.skin_cover, 0.0, 1.0);
  e.on_ground = env.get<bool>("on_ground", e.on_ground);
  e.ground_height_mm = env.get_number("ground_height_mm", e.ground_height_mm, -1e5, 1e5);
  JobNode tissue = root.child("tissue");
  TissueDrying& t = job.settings.tissue;
  t.initial_moisture = dry_basis_moisture(
      0.01 * tissue.get_number("initial_water_percent", 100.0 * wet_basis_moisture(t.initial_moisture), 1.0, 95.0));
  t.reference_diffusivity_m2_per_s =
      tissue.get_number("diffusivity_m2_per_s", t.reference_diffusivity_m2_per_s, 1e-13, 1e-7);
  t.diffusivity_drying_exponent =
      tissue.get_number("diffusivity_drying_exponent", t.diffusivity_drying_exponent, 0.0, 20.0);
  t.shrinkage_efficiency = tissue.get_number("shrinkage_efficiency", t.shrinkage_efficiency, 0.0, 1.0);
  t.skin_permeance_m_per_s = tissue.get_number("skin_permeance_m_per_s", t.skin_permeance_m_per_s, 1e-9, 10.0);
  job.settings.deform = root.get<bool>("deform", true);
  job.deform_every = root.get_integer("deform_every_steps", job.deform_every, 1, 1000);
  job.skin = load_skin_job(a, root.child("skin"));
  job.skin_motion = load_skin_motion_job(a, root.child("skin"));
  job.figure8 = a.given("--figure8") ? a.figure8 : root.child("skin").get<bool>("figure8", a.figure8);
  return job;
}

JobKind mummify_job_kind() {
  JobKind kind;
  kind.name = "mummify";
  kind.prepare = [](const JobNode& request, const JobContext& context) {
    const bool pictures = request.get<bool>("pictures", false);
    const long long picture_size = request.get_integer("picture_size", 480, 64, 2048);
    const MummifyArgs defaults;
    const MummifyJob job = read_mummify_job(request.child("job"), defaults);
    nlohmann::json file = context.request.contains("job") ? context.request["job"] : nlohmann::json::object();
    if (!job.model.empty()) {
      // A body model folder is named relative to the served folder and must stay inside it.
      const ServedPath p = resolve_served_path(context.served_root, job.model);
      if (p.problem != ServedPathProblem::none) {
        throw ApiError(p.problem == ServedPathProblem::outside ? 403 : 400, p.message, "/job/body/model");
      }
      file["body"]["model"] = p.path.string();
    }
    const std::filesystem::path job_file = context.output_folder / "job.json";
    write_file_atomic(job_file, file.dump(2) + "\n");
    PreparedJob out;
    out.arguments = {"mummify",        job_file.string(),           "-o", context.output_folder.string(),
                     "--picture-size", std::to_string(picture_size)};
    if (!pictures) out.arguments.push_back("--no-pictures");
    out.summary = {{"body", job.model.empty() ? job.phantom + " (" + job.size + ")" : job.model},
                   {"days", job.days},
                   {"frames", job.frames},
                   {"temperature_c", job.settings.environment.air_temperature_c},
                   {"humidity_percent", 100.0 * job.settings.environment.relative_humidity}};
    return out;
  };
  return kind;
}

}  // namespace forensim::cli
