#pragma once
/// The mummify job file (version 1) and its loader, shared by `forensim mummify` and the server's "mummify" job
/// kind so both accept exactly the same keys and ranges:
///   {"version": 1, "body": {"phantom": "arm"|"head", "size": "small"|"paper"|"fine", "model": folder},
///    "days", "frames", "step_hours", "deform", "deform_every_steps",
///    "environment": {"temperature_c", "humidity_percent", "wind_m_per_s", "body_diameter_m", "skin_cover",
///                    "on_ground", "ground_height_mm"},
///    "tissue": {"initial_water_percent", "diffusivity_m2_per_s", "diffusivity_drying_exponent",
///               "shrinkage_efficiency", "skin_permeance_m_per_s"},
///    "skin": {"gravity" (default: the body model's pose; also sets the environment's up to its opposite),
///    "contact_distance_mm", "map_resolution", "blood_fill", "residual_fill", "transition_mm",
///             "contact_capacity", "oxygen", "drying_boost", "oxygen_decay_hours",
///             "pbd", "figure8", "substeps", "iterations", "bending_interval", "skin_shrinkage",
///             "wrinkle": {"set": 0|1|2} or {"r_max_relative", "damping"},
///             "slippage": {"stiffness", "decrease_below", "zero_below"}}}

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "core/job.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "mummify_skin.hpp"
#include "mummify_skin_motion.hpp"
#include "server/job_manager.hpp"

namespace forensim::cli {

/// Command-line values of `forensim mummify`; those given on the command line win over the job file's.
struct MummifyArgs {
  std::string job, phantom = "arm", size = "small", model, out = "out/mummify";
  double days = 21.0, step_hours = 12.0, temperature = 35.0, humidity = 30.0, wind = 1.0;
  int frames = 6, picture_size = 480, map_size = 512;
  int wrinkle_set = 1;          ///< --wrinkle-set: Figure 8's wrinkle controls (0, 1, 2)
  std::vector<double> gravity;  ///< --gravity x y z (empty: the job's, or down)
  double contact_mm = 3.0;
  bool resume = false, no_pictures = false, figure8 = false;
  CLI::App* sub = nullptr;  ///< null: nothing was given on a command line (the server)
  bool given(const std::string& option) const { return sub != nullptr && sub->get_option(option)->count() > 0; }
};

/// A run's description: the job file (or defaults), with command-line options taking precedence.
struct MummifyJob {
  std::string phantom, size, model;
  double days = 0.0, step_hours = 0.0;
  int frames = 0;
  long long deform_every = 4;  ///< quasi-static shape solved every this many steps (and at frames)
  DesiccationSettings settings;
  SkinShadingJob skin;        ///< the "skin" object: livor mortis start state and shading
  SkinMotionJob skin_motion;  ///< the "skin" object: the position-based skin (sections 8.1, 8.2)
  bool figure8 = false;       ///< "skin"/"figure8": also run Figure 8's three wrinkle controls, for comparison
};

/// Reads a mummify job from `root` (a job file's root, or the "job" object of a server request). Throws
/// JobError naming the key for wrong types and values out of range. Does not call check_all_used().
MummifyJob read_mummify_job(const JobNode& root, const MummifyArgs& a);

/// The server's "mummify" job kind. Request (beside "kind" and "output"): "job" (the job file above; a
/// "body/model" folder must lie inside the served folder), "pictures" (render the moisture and shrinkage
/// pictures at the end; default false), "picture_size" (64..2048, default 480).
JobKind mummify_job_kind();

}  // namespace forensim::cli
