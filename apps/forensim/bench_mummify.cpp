// `forensim bench mummify`: the cost of one frame of the desiccation system as the paper counts it (Frerichs,
// Vidler and Gatzidis 2020, Table 2, an i7 at 3.4 GHz: per frame the dehydration step, the volume deformation
// step, the skin deformation step and the skin's shading), on the phantom arm and head at the chosen size
// (`paper`: the paper's model sizes, Table 1), beside forensim's goal of 30 times faster than the paper.
//
// What is timed, per phantom, in the default environment and with the default skin of `forensim mummify`, from
// the state of day 5 of a run (12 h steps, the shape and the skin advanced as mummify does), each row the
// median of --repeat runs of the same work from the same state:
// - moisture step: one implicit moisture step of 12 h;
// - volume (shape) step: the quasi-static shape solve after it (from the shape of two days before);
// - skin step: one position-based step of the skin (src/pbd) onto the new shape, with the new moisture;
// - skin shading: the skin's moisture ratio and colour (two-layer shading, section 8.3) for the new state;
// - per frame: the four together, as one frame of the paper;
// - skin motion per shape solve: the `substeps` skin steps `forensim mummify` runs per shape solve, for scale.
// Thread count: forensim's worker threads (--threads, all cores by default); CHOLMOD's BLAS follows
// OMP_NUM_THREADS / OPENBLAS_NUM_THREADS.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_registry.hpp"
#include "body/phantom_model.hpp"
#include "core/parallel.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "mummify_skin.hpp"
#include "mummify_skin_motion.hpp"

namespace forensim::cli {
namespace {

constexpr double hour = 3600.0;

struct PaperFrame {
  double frame_s, dehydration_s, deformation_s, skin_s;
};

void bench_phantom(const std::string& phantom, const BenchOptions& options, const PaperFrame& paper,
                   std::vector<BenchRow>& rows) {
  const std::string label = phantom + " " + options.size;
  const std::string ref = "Table 2, i7 3.4 GHz";
  const bool paper_size = options.size == "paper";
  auto paper_or_none = [&](double s) { return paper_size ? s : -1.0; };
  auto goal_or_none = [&](double s) { return paper_size ? s / 30.0 : -1.0; };
  auto start = std::chrono::steady_clock::now();
  const DesiccationModel model =
      make_desiccation_model(make_phantom_model(phantom_model_size(phantom, options.size)), DesiccationSettings{});
  const double seconds_model = seconds_since(start);
  const std::string counts = std::to_string(model.body.volume.vertex_count()) + " nodes, " +
                             std::to_string(model.body.volume.tet_count()) + " tets, " +
                             std::to_string(model.body.skin.triangles.size()) + " skin triangles";
  std::printf("  %s: %s (model built in %.1f s; %d threads)\n", label.c_str(), counts.c_str(), seconds_model,
              thread_count());
  std::fflush(stdout);

  start = std::chrono::steady_clock::now();
  const double phi0 = model.settings.tissue.initial_moisture;
  const MummifySkin shading(model.body, phi0, SkinShadingJob{});
  const SkinMotionJob motion_job;
  MummifySkinMotion motion(model.body, phi0, motion_job);
  SkinMotionJob single_job = motion_job;
  single_job.substeps = 1;
  MummifySkinMotion single(model.body, phi0, single_job);
  DesiccationSolver solver(model);
  const double seconds_setup = seconds_since(start);

  // Day 5 as mummify runs it: 12 h steps, the shape and the skin every 4th step.
  DesiccationState state = initial_desiccation_state(model);
  start = std::chrono::steady_clock::now();
  std::vector<Vec3> shape = state.positions;
  for (int step = 1; step <= 10; ++step) {
    const bool deform = step % 4 == 0;
    solver.step(state, 12 * hour, deform);
    if (deform) {
      motion.advance(shape, state);
      shape = state.positions;
    }
  }
  std::printf("  %s: day 5 reached in %.1f s\n", label.c_str(), seconds_since(start));
  std::fflush(stdout);
  const std::string skin_bytes = motion.checkpoint_bytes();

  // The parts of one frame, each repeated from the day-5 state.
  const std::size_t skin_vertices = model.body.skin.vertex_count();
  std::vector<double> moisture_s, volume_s, skin_s, shading_s, frame_s, substeps_s;
  DesiccationStepReport last;
  SkinMotionReport skin_report;
  for (int r = 0; r < options.repetitions + 1; ++r) {
    DesiccationState s = state;
    last = solver.step(s, 12 * hour, true);
    single.restore(skin_bytes, state, "bench");
    const auto t1 = std::chrono::steady_clock::now();
    skin_report = single.advance(state.positions, s);
    const auto t2 = std::chrono::steady_clock::now();
    const SkinFrame frame = shading.frame(s, single.positions());
    if (frame.colours.size() != skin_vertices) return;
    const auto t3 = std::chrono::steady_clock::now();
    if (r == 0) continue;  // the first run warms caches
    moisture_s.push_back(last.seconds_diffusion);
    volume_s.push_back(last.seconds_deformation);
    skin_s.push_back(std::chrono::duration<double>(t2 - t1).count());
    shading_s.push_back(std::chrono::duration<double>(t3 - t2).count());
    frame_s.push_back(last.seconds_diffusion + last.seconds_deformation +
                      std::chrono::duration<double>(t3 - t1).count());
  }
  for (int r = 0; r < options.repetitions; ++r) {
    DesiccationState s = state;
    solver.step(s, 12 * hour, true);
    motion.restore(skin_bytes, state, "bench");
    substeps_s.push_back(motion.advance(state.positions, s).seconds);
  }
  BenchTiming t = summarise_samples(moisture_s);
  rows.push_back({label + ": moisture step (12 h)", t.median_s, t.min_s, paper_or_none(paper.dehydration_s), ref,
                  goal_or_none(paper.dehydration_s), std::to_string(last.diffusion_iterations) + " CG iterations"});
  t = summarise_samples(volume_s);
  rows.push_back({label + ": volume (shape) step", t.median_s, t.min_s, paper_or_none(paper.deformation_s), ref,
                  goal_or_none(paper.deformation_s),
                  std::to_string(last.deformation_iterations) + " Newton, " +
                      std::to_string(last.deformation_cg_iterations) + " CG iterations"});
  t = summarise_samples(skin_s);
  const SkinModel& skin_model = single.model();
  rows.push_back({label + ": skin step", t.median_s, t.min_s, paper_or_none(paper.skin_s), ref,
                  goal_or_none(paper.skin_s),
                  std::to_string(skin_vertices) + " vertices, " + std::to_string(skin_model.settings.iterations) +
                      " iterations, " + std::to_string(skin_report.collisions) + " collisions, " +
                      std::to_string(skin_report.pulled) + " pulls"});
  t = summarise_samples(shading_s);
  rows.push_back({label + ": skin shading", t.median_s, t.min_s, -1.0, "", -1.0,
                  "moisture ratio and two-layer colour per vertex"});
  t = summarise_samples(frame_s);
  rows.push_back({label + ": per frame (the four above)", t.median_s, t.min_s, paper_or_none(paper.frame_s), ref,
                  goal_or_none(paper.frame_s), "paper's frame also includes its skin rendering"});
  t = summarise_samples(substeps_s);
  rows.push_back({label + ": skin motion per shape solve", t.median_s, t.min_s, -1.0, "", -1.0,
                  std::to_string(motion_job.substeps) + " skin steps, as forensim mummify runs them"});
  rows.push_back(
      {label + ": set-up (once per run)", seconds_setup, seconds_setup, -1.0, "", -1.0,
       "skin model and colouring, livor start state, solvers; peak memory so far " + format_mib(peak_rss_bytes())});
}

const RegisterBench mummify_bench{
    BenchTarget{"mummify",
                "one frame of the desiccation system (moisture step, volume step, skin step, skin shading) on the "
                "arm and head phantoms, beside Table 2 of Frerichs et al. 2020",
                [](const BenchOptions& options) {
                  std::vector<BenchRow> rows;
                  bench_phantom("arm", options, {2.933, 0.372, 2.563, 0.173}, rows);
                  bench_phantom("head", options, {10.930, 1.463, 8.156, 1.221}, rows);
                  return rows;
                }}};

}  // namespace
}  // namespace forensim::cli
