// forensim bench reconstruct: the craniofacial reconstruction's paths beside the paper's "about an hour" for a
// whole reconstruction (Kähler, Haber and Seidel 2003, section 6; mostly interactive landmark work) and the
// project's goals (issue 8): from a CT to a reconstructed head with automatic landmarks in under 5 s, split
// into its phases (bone surface at its half-maximum height, component selection and decimation, registration and
// landmark detection, the fit: depth vectors, warp with interpolated landmarks, muscles, violation counts); from a
// skull mesh with landmarks to the head; and the interactive case, the head updated after one landmark moves, in under
// 200 ms. The template head is built once beforehand (it is the same for every reconstruction) for the phases; the
// headsq CT's path is also timed whole, as forensim reconstruct runs it, the template built in the run (full and coarse
// detail). CTs: the built-in CT phantom, and the headsq CT of the shared data when the data folder holds it.

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_registry.hpp"
#include "core/data_dir.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/reconstruction_uncertainty.hpp"
#include "craniofacial/skull_completion.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/template_carry.hpp"
#include "craniofacial/template_file.hpp"
#include "craniofacial/template_head.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "reconstruct/reconstruct_job.hpp"
#include "volume/iso_surface.hpp"
#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

constexpr double kPaperS = 3600.0;  // "about an hour" per reconstruction
const char* const kPaperRef = "Kähler et al. 2003, section 6: about an hour";

// CPU seconds of all the process's threads so far: the machine may be shared, and wall times on a loaded
// machine overstate the work.
double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// time_repeated, with the mean CPU time per run (all threads) in `cpu_s`.
BenchTiming timed(int repetitions, const std::function<void()>& fn, double& cpu_s) {
  const double c0 = process_cpu_s();
  const BenchTiming t = time_repeated(repetitions, fn);
  cpu_s = (process_cpu_s() - c0) / std::max(repetitions, 1);
  return t;
}

std::string cpu_text(double cpu_s) {
  char buf[64];
  if (cpu_s < 1.0) {
    std::snprintf(buf, sizeof buf, "cpu %.0f ms/run; ", 1e3 * cpu_s);
  } else {
    std::snprintf(buf, sizeof buf, "cpu %.2f s/run; ", cpu_s);
  }
  return buf;
}

std::string count_text(const char* what, std::size_t n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%zu %s", n, what);
  return buf;
}

/// The CT path's phases for one volume, each timed `repetitions` times (median), then the sum of the medians.
void bench_ct(const std::string& label, const ScalarGrid& volume, const TemplateHead& head, const TissueDepths& depths,
              const BenchOptions& options, std::vector<BenchRow>& rows) {
  double c_edge = 0.0, c_mesh = 0.0, c_detect = 0.0, c_fit = 0.0, c_violations = 0.0;
  // As forensim reconstruct on its defaults: the bone surface at its half-maximum height (found from the 126 HU
  // surface); the 126 HU iso-surface alone (--bone-iso 1150) timed beside it.
  const SkullInputOptions edge_options = skull_input_options(ReconstructJob{});
  BoneSurface bone;
  const BenchTiming t_edge = timed(
      options.repetitions, [&] { bone = extract_bone_surface(volume, label, edge_options); }, c_edge);
  BoneSurface iso;
  double c_plain = 0.0;
  const BenchTiming t_plain = timed(
      options.repetitions, [&] { iso = extract_bone_surface(volume, label); }, c_plain);
  const TriMesh& surface = bone.surface;
  SkullInputOptions skull_options;
  skull_options.bone_iso_value = bone.iso_value;
  Skull skull;
  const BenchTiming t_mesh = timed(
      options.repetitions, [&] { skull = skull_from_mesh(surface, label, skull_options); }, c_mesh);
  // The scan's field of view, as forensim reconstruct passes it: the registration counts only the template's
  // parts the scan can show (headsq is cut below the jaw and above the brows).
  skull.field_of_view = ScanFieldOfView::of_volume(volume);
  LandmarkDetectionOptions detection_options;
  detection_options.registration.similarity.target_view = skull.field_of_view;
  std::unique_ptr<LandmarkDetection> detection;
  BenchTiming t_detect = timed(
      options.repetitions,
      [&] {
        detection = std::make_unique<LandmarkDetection>(detect_template_landmarks(head, skull.mesh, detection_options));
      },
      c_detect);
  // Landmarks the scan did not see lie on the registered template, whose missing part completes the skull (as
  // forensim reconstruct does; timed with the detection).
  const std::size_t scan_triangles = skull.mesh.triangles.size();
  bool unseen = false;
  for (const DetectedLandmark& d : detection->details) unseen = unseen || !d.in_view;
  if (unseen) {
    double c_complete = 0.0;
    const BenchTiming t_complete = timed(
        1,
        [&] { skull.mesh = complete_skull(skull.mesh, skull.field_of_view, head.skull, detection->registration).mesh; },
        c_complete);
    c_detect += c_complete;
    t_detect.median_s += t_complete.median_s;
    t_detect.min_s += t_complete.min_s;
  }
  // The template carried onto the skull by the registration (template_carry.hpp), as forensim reconstruct does.
  double c_carry = 0.0;
  std::unique_ptr<TemplateHead> carried;
  const BenchTiming t_carry = timed(
      options.repetitions,
      [&] { carried = std::make_unique<TemplateHead>(carry_template_head(head, detection->registration)); }, c_carry);
  std::unique_ptr<Reconstruction> reconstruction;
  ReconstructionOptions fit_only;
  fit_only.fit.count_violations = false;
  const BenchTiming t_fit = timed(
      options.repetitions,
      [&] {
        reconstruction = std::make_unique<Reconstruction>(*carried, skull.mesh, detection->landmarks, depths, fit_only);
      },
      c_fit);
  const BenchTiming t_violations = timed(
      options.repetitions, [&] { reconstruction->recount_violations(); }, c_violations);
  const std::string voxels = count_text("voxels", volume.voxel_count());
  char threshold[96] = "";
  if (bone.seed_iso_value) {
    std::snprintf(threshold, sizeof threshold, " at %.0f (half-maximum height of %zu profiles)", bone.iso_value,
                  bone.threshold_profiles);
  }
  rows.push_back({label + ": bone surface at its half-maximum height", t_edge.median_s, t_edge.min_s, -1.0, "", -1.0,
                  cpu_text(c_edge) + voxels + " -> " + count_text("triangles", surface.triangles.size()) + threshold});
  rows.push_back({label + ": bone iso-surface at 1150 alone (--bone-iso)", t_plain.median_s, t_plain.min_s, -1.0, "",
                  -1.0,
                  cpu_text(c_plain) + count_text("triangles", iso.surface.triangles.size()) + "; not in the sum"});
  rows.push_back({label + ": components, decimation", t_mesh.median_s, t_mesh.min_s, -1.0, "", -1.0,
                  cpu_text(c_mesh) + count_text("skull triangles", scan_triangles)});
  char reg[200];
  std::snprintf(reg, sizeof reg, "%s%zu landmarks; similarity rms %.2f mm, non-rigid rms %.2f mm%s",
                cpu_text(c_detect).c_str(), detection->landmarks.size(), detection->registration.similarity_rms_mm,
                detection->registration.rms_mm, unseen ? "; skull completed outside the scan" : "");
  rows.push_back(
      {label + ": registration, landmark detection", t_detect.median_s, t_detect.min_s, -1.0, "", -1.0, reg});
  rows.push_back({label + ": template carried onto the skull", t_carry.median_s, t_carry.min_s, -1.0, "", -1.0,
                  cpu_text(c_carry) + count_text("skin vertices", head.skin.positions.size()) + ", " +
                      count_text("skull vertices", head.skull.positions.size()) + " mapped"});
  const TemplateFitResult& fit = reconstruction->fit();
  rows.push_back({label + ": fit (depth vectors, warp, muscles)", t_fit.median_s, t_fit.min_s, -1.0, "", -1.0,
                  cpu_text(c_fit) + count_text("pairs", fit.targets.size()) + " (" +
                      std::to_string(fit.given_pair_count) + " given)"});
  const ReconstructionResult& result = reconstruction->result();
  rows.push_back({label + ": skull/skin violation counts", t_violations.median_s, t_violations.min_s, -1.0, "", -1.0,
                  cpu_text(c_violations) + std::to_string(result.violations_given_only.total()) + " -> " +
                      std::to_string(result.violations_final.total())});
  const double total =
      t_edge.median_s + t_mesh.median_s + t_detect.median_s + t_carry.median_s + t_fit.median_s + t_violations.median_s;
  const double total_min =
      t_edge.min_s + t_mesh.min_s + t_detect.min_s + t_carry.min_s + t_fit.min_s + t_violations.min_s;
  rows.push_back(
      {label + ": CT to head, automatic landmarks (sum)", total, total_min, kPaperS, kPaperRef, 5.0,
       cpu_text(c_edge + c_mesh + c_detect + c_carry + c_fit + c_violations) + "the template head built beforehand"});
}

/// The whole of forensim reconstruct's path from a CT, the template built too (as every run builds it), for one
/// template detail: the template's skin, atlas and muscles built beside the CT's skull, the template's skull and
/// the landmark detection (and the skull's completion), then the halves joined and the head fitted with its
/// violation counts. Each run from the volume in memory.
BenchRow bench_ct_end_to_end(const std::string& label, const ScalarGrid& volume, const std::string& detail,
                             const TissueDepths& depths, const BenchOptions& options) {
  const TemplateHeadOptions template_options = template_head_options(detail);
  std::size_t landmarks = 0, violations = 0;
  double rms = 0.0;
  double cpu = 0.0;
  const BenchTiming t = timed(
      options.repetitions,
      [&] {
        Skull skull;
        std::optional<LandmarkDetection> detection;
        const TemplateHead head = make_template_head_beside(template_options, [&](const TemplateHead& skull_part) {
          skull = skull_from_volume(volume, label, skull_input_options(ReconstructJob{}));
          ScanLandmarkDetection found = detect_scan_landmarks(skull_part, skull.mesh, skull.field_of_view);
          detection = std::move(found.detection);
          if (found.completion) skull.mesh = std::move(found.completion->mesh);
        });
        const TemplateHead carried = carry_template_head(head, detection->registration);
        const Reconstruction reconstruction(carried, skull.mesh, detection->landmarks, depths);
        landmarks = detection->landmarks.size();
        rms = detection->registration.rms_mm;
        violations = reconstruction.result().violations_final.total();
      },
      cpu);
  char note[200];
  std::snprintf(note, sizeof note, "%s%zu landmarks, non-rigid rms %.2f mm, %zu violations left; %d threads",
                cpu_text(cpu).c_str(), landmarks, rms, violations, thread_count());
  return {label + ": CT to head with the " + detail + " template built (forensim reconstruct)",
          t.median_s,
          t.min_s,
          kPaperS,
          kPaperRef,
          5.0,
          note};
}

/// forensim reconstruct --template FILE's path from a CT: the full template read from its file beside the built-in
/// template's skull (the landmarks' reference) and the CT's skull, the detection, then the fit with its violation
/// counts. The file is written once beforehand.
BenchRow bench_ct_template_file(const std::string& label, const ScalarGrid& volume, const TissueDepths& depths,
                                const BenchOptions& options) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "forensim_bench_template.cbor";
  write_template_head(file, make_template_head(template_head_options("full")));
  const TemplateHeadOptions reference_options = template_head_options("full");
  std::size_t landmarks = 0, violations = 0;
  double cpu = 0.0;
  const BenchTiming t = timed(
      options.repetitions,
      [&] {
        TemplateHead head, reference;
        Skull skull;
        parallel_for(
            0, 2,
            [&](std::size_t part) {
              if (part == 0) {
                head = read_template_head(file);
              } else {
                reference = make_template_skull(reference_options);
                skull = skull_from_volume(volume, label, skull_input_options(ReconstructJob{}));
              }
            },
            1);
        ScanLandmarkDetection found = detect_scan_landmarks(reference, skull.mesh, skull.field_of_view);
        if (found.completion) skull.mesh = std::move(found.completion->mesh);
        // The file holds the built-in template, whose skull is the reference's: carried as forensim reconstruct does.
        const TemplateHead carried = carry_template_head(head, found.detection.registration);
        const Reconstruction reconstruction(carried, skull.mesh, found.detection.landmarks, depths);
        landmarks = found.detection.landmarks.size();
        violations = reconstruction.result().violations_final.total();
      },
      cpu);
  std::filesystem::remove(file);
  char note[200];
  std::snprintf(note, sizeof note, "%s%zu landmarks, %zu violations left; the template file written beforehand",
                cpu_text(cpu).c_str(), landmarks, violations);
  return {label + ": CT to head with the full template from its file (forensim reconstruct --template)",
          t.median_s,
          t.min_s,
          kPaperS,
          kPaperRef,
          5.0,
          note};
}

std::vector<BenchRow> run_reconstruct(const BenchOptions& options) {
  std::vector<BenchRow> rows;
  Stopwatch watch;
  const TemplateHead head = make_template_head();
  rows.push_back({"template head (built once)", watch.seconds(), watch.seconds(), -1.0, "", -1.0,
                  count_text("skin vertices", head.skin.positions.size()) + ", " +
                      count_text("skull triangles", head.skull.triangles.size())});
  const TissueDepths depths = select_tissue_depths(built_in_tissue_depth_table(default_tissue_depth_table_name()));

  // (a) CT to head.
  watch.lap();
  const ScalarGrid phantom = make_ct_head_phantom();
  rows.push_back({"CT phantom: volume generated (not timed in the path)", watch.lap(), 0.0, -1.0, "", -1.0,
                  count_text("voxels", phantom.voxel_count())});
  bench_ct("CT phantom", phantom, head, depths, options, rows);
  const std::filesystem::path headsq = shared_data_dir() / "ct-head-headsq" / "quarter.nhdr";
  if (std::filesystem::exists(headsq)) {
    const BenchTiming t_read = time_repeated(1, [&] { (void)read_volume(headsq); });
    rows.push_back({"headsq CT: read", t_read.median_s, t_read.min_s, -1.0, "", -1.0, headsq.string()});
    const ScalarGrid volume = read_volume(headsq);
    bench_ct("headsq CT", volume, head, depths, options, rows);
    // As forensim reconstruct runs it: the template built in the run (the default full detail, and coarse).
    for (const char* detail : {"full", "coarse"})
      rows.push_back(bench_ct_end_to_end("headsq CT", volume, detail, depths, options));
    rows.push_back(bench_ct_template_file("headsq CT", volume, depths, options));
  }

  // (b) Skull mesh with landmarks to head: the built-in skull and its landmarks.
  const LandmarkSet landmarks = template_skull_landmarks(head);
  std::unique_ptr<Reconstruction> reconstruction;
  ReconstructionOptions fit_only;
  fit_only.fit.count_violations = false;
  double c_mesh = 0.0;
  const BenchTiming t_mesh = timed(
      options.repetitions,
      [&] { reconstruction = std::make_unique<Reconstruction>(head, head.skull, landmarks, depths, fit_only); },
      c_mesh);
  rows.push_back({"skull mesh + landmarks to head (built-in skull)", t_mesh.median_s, t_mesh.min_s, kPaperS, kPaperRef,
                  -1.0, cpu_text(c_mesh) + count_text("pairs", reconstruction->fit().targets.size())});

  // (c) The interactive case: one landmark moves, the head (skin, muscle grids and shapes) follows. The first move
  // after a fit also makes the points' cardinal functions (the fit itself only warps them); then alternating
  // between two positions so every call changes the head.
  {
    Stopwatch first;
    const std::size_t changed = reconstruction->move_landmark("pg", landmarks.at("pg").position_mm + Vec3(0, -1, 0));
    const double s = first.seconds();
    rows.push_back({"first update after the fit (pg; cardinal functions made)", s, s, -1.0, "", 0.2,
                    count_text("warp targets changed", changed)});
  }
  for (const char* name : {"pg", "v"}) {
    const Vec3 start = landmarks.at(name).position_mm;
    int k = 0;
    std::size_t changed = 0;
    reconstruction->move_landmark(name, start + Vec3(0, -2, 1));  // warm-up
    double cpu = 0.0;
    const BenchTiming t = timed(
        std::max(options.repetitions, 5),
        [&] {
          changed = reconstruction->move_landmark(name, start + (k++ % 2 == 0 ? Vec3(1.5, -3, 2) : Vec3(0, -2, 1)));
        },
        cpu);
    rows.push_back({std::string("update after one landmark moves (") + name + ")", t.median_s, t.min_s, -1.0, "", 0.2,
                    cpu_text(cpu) + count_text("warp targets changed", changed)});
  }
  FaceGuides guides;
  guides.mouth_corner_left_mm = reconstruction->result().skin_landmarks.at("ch'_L").position_mm.x() + 2.0;
  reconstruction->set_guides(guides);
  double c_guided = 0.0;
  int k = 0;
  const BenchTiming t_guided = timed(
      std::max(options.repetitions, 5),
      [&] {
        reconstruction->move_landmark("gn", landmarks.at("gn").position_mm + Vec3(0, k++ % 2 == 0 ? -1.0 : -2.0, 0));
      },
      c_guided);
  rows.push_back({"update after one landmark moves, with guides (gn)", t_guided.median_s, t_guided.min_s, -1.0, "", 0.2,
                  cpu_text(c_guided) + "second warp re-applied; " + std::to_string(thread_count()) + " threads"});
  reconstruction->set_guides(std::nullopt);

  // Beyond the paper: the uncertainty ensemble (depths drawn from the table's SDs), 16 members.
  double c_ensemble = 0.0;
  ReconstructionUncertainty spread;
  const BenchTiming t_ensemble = timed(
      options.repetitions, [&] { spread = reconstruction_uncertainty(*reconstruction, 16, 1); }, c_ensemble);
  char ens[96];
  std::snprintf(ens, sizeof ens, "max spread %.2f mm, mean %.2f mm", spread.max_spread_mm, spread.mean_spread_mm);
  rows.push_back({"uncertainty ensemble, 16 members", t_ensemble.median_s, t_ensemble.min_s, -1.0, "", -1.0,
                  cpu_text(c_ensemble) + ens});
  return rows;
}

const RegisterBench reconstruct_bench{
    BenchTarget{"reconstruct",
                "craniofacial reconstruction: CT to head with automatic landmarks (phases), skull mesh with "
                "landmarks to head, and the update after one landmark moves, beside Kähler et al. 2003's hour",
                run_reconstruct}};

}  // namespace
}  // namespace forensim::cli
