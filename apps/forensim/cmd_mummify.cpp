// forensim mummify: the desiccation simulation (Frerichs, Vidler and Gatzidis 2020, sections 6 to 8):
// moisture evaporating through the skin and diffusing in the flesh of a body model, the shrinkage of the
// volume it causes, and the skin over it with its colour from the livor mortis start state to dried, dark
// brown skin (section 8.3). Writes the animated skin (GLB), .pvd/.vtu series of the volume and the skin,
// CSV curves, plots and renders into a run folder; checkpoints at every frame so an interrupted run
// continues with --resume.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include "body/body_model_io.hpp"
#include "body/phantom_model.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/job.hpp"
#include "core/progress.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "desiccation/curve_plot.hpp"
#include "desiccation/desiccation_pictures.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "image/png_io.hpp"
#include "mummify_checkpoint.hpp"
#include "mummify_job.hpp"
#include "mummify_run.hpp"
#include "mummify_skin.hpp"
#include "mummify_skin_checks.hpp"
#include "mummify_skin_motion.hpp"
#include "pbd/wrinkle_measure.hpp"
#include "pictures.hpp"
#include "render/camera.hpp"
#include "render/colour_bar.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "tet_io/pvd_writer.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim::cli {

namespace {

/// One row of the curves: day, totals, per-part water/mass/volume.
struct CurveRow {
  double day = 0.0;
  DesiccationTotals totals;
};

std::string csv_header(const std::vector<std::string>& parts) {
  std::string h = "day,water_kg,total_kg,volume_cm3,water_percent,mass_percent,volume_percent";
  for (const std::string& p : parts) h += "," + p + "_water_percent," + p + "_mass_kg," + p + "_volume_cm3";
  return h + "\n";
}

std::string csv_text(const std::vector<CurveRow>& rows, const std::vector<std::string>& parts) {
  std::ostringstream out;
  out << csv_header(parts);
  out.precision(10);
  const DesiccationTotals& t0 = rows.front().totals;
  for (const CurveRow& r : rows) {
    const DesiccationTotals& t = r.totals;
    out << r.day << ',' << t.water_kg << ',' << t.total_kg << ',' << t.volume_mm3 / 1000.0 << ','
        << 100.0 * t.water_kg / t0.water_kg << ',' << 100.0 * t.total_kg / t0.total_kg << ','
        << 100.0 * t.volume_mm3 / t0.volume_mm3;
    for (std::size_t p = 0; p < t.part_water_kg.size(); ++p) {
      const double w0 = t0.part_water_kg[p];
      out << ',' << (w0 > 0.0 ? 100.0 * t.part_water_kg[p] / w0 : 0.0) << ',' << t.part_total_kg[p] << ','
          << t.part_volume_mm3[p] / 1000.0;
    }
    out << '\n';
  }
  return out.str();
}

void write_frame(RunFolder& run, PvdSeries& series, const DesiccationModel& model, const DesiccationState& state,
                 int frame) {
  TetMesh mesh = model.body.volume;
  const std::size_t n = mesh.vertex_count();
  std::vector<Vec3> displacement(n);
  for (std::size_t i = 0; i < n; ++i) displacement[i] = state.positions[i] - mesh.positions[i];
  mesh.positions = state.positions;
  mesh.vertex_fields.scalars["moisture"] = state.node_moisture;
  std::vector<double> water_percent(n);
  for (std::size_t i = 0; i < n; ++i) water_percent[i] = 100.0 * wet_basis_moisture(state.node_moisture[i]);
  mesh.vertex_fields.scalars["water_percent"] = water_percent;
  mesh.vertex_fields.vectors["displacement"] = displacement;
  mesh.tet_fields.scalars["target_shrinkage_ratio"] = tet_volume_ratio(model, state);
  std::vector<double> ratio(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& k = mesh.tets[t];
    const Vec3 &a = mesh.positions[static_cast<std::size_t>(k[0])], &b = mesh.positions[static_cast<std::size_t>(k[1])],
               &c = mesh.positions[static_cast<std::size_t>(k[2])], &d = mesh.positions[static_cast<std::size_t>(k[3])];
    ratio[t] = (b - a).dot((c - a).cross(d - a)) / 6.0 / model.tet_rest_volume_mm3[t];
  }
  mesh.tet_fields.scalars["shrinkage_ratio"] = ratio;
  if (!model.body.tet_parts.empty()) {
    std::vector<double> part(model.body.tet_parts.begin(), model.body.tet_parts.end());
    mesh.tet_fields.scalars["part"] = part;
  }
  char name[64];
  std::snprintf(name, sizeof name, "volume/frame_%04d.vtu", frame);
  VtuOptions options;
  options.compress = true;
  options.field_precision = VtuPrecision::float32;
  write_vtu(run.file(name), mesh, options);
  run.add_output(name);
  series.add(state.time_s / 86400.0, name);
}

void write_plots(RunFolder& run, const std::vector<CurveRow>& rows, const std::vector<std::string>& parts) {
  const DesiccationTotals& t0 = rows.front().totals;
  CurveSeries mass{"total mass", {}, {}}, water{"water", {}, {}}, volume{"volume", {}, {}};
  std::vector<CurveSeries> part_series;
  for (const std::string& p : parts) part_series.push_back({p, {}, {}});
  for (const CurveRow& r : rows) {
    for (CurveSeries* s : {&mass, &water, &volume}) s->x.push_back(r.day);
    mass.y.push_back(100.0 * r.totals.total_kg / t0.total_kg);
    water.y.push_back(100.0 * r.totals.water_kg / t0.water_kg);
    volume.y.push_back(100.0 * r.totals.volume_mm3 / t0.volume_mm3);
    for (std::size_t p = 0; p < part_series.size() && p < r.totals.part_water_kg.size(); ++p) {
      part_series[p].x.push_back(r.day);
      part_series[p].y.push_back(t0.part_water_kg[p] > 0 ? 100.0 * r.totals.part_water_kg[p] / t0.part_water_kg[p]
                                                         : 0.0);
    }
  }
  CurvePlotStyle style;
  style.title = "Mass, water and volume";
  style.x_label = "days";
  style.y_label = "% of initial";
  style.y_min = 0.0;
  style.y_max = 100.0;
  write_png(run.file("curves.png"),
            plot_curves({mass, water, volume}, style,
                        {{60.0, 70.0, "Papageorgopoulou et al. 2015: ~30 % mass lost in 2 months"}}));
  run.add_output("curves.png");
  if (!part_series.empty()) {
    style.title = "Water per part";
    write_png(run.file("curves_parts.png"), plot_curves(part_series, style));
    run.add_output("curves_parts.png");
  }
}

std::vector<CurveRow> read_rows(const std::filesystem::path& csv, const DesiccationModel& model, double up_to_day) {
  // Only the totals needed for the CSV and the plots are restored; percentages are recomputed from row 0. A
  // resumed run rewrites the file from these rows, so a missing, foreign or damaged file is an error, not rows
  // silently lost.
  const std::string source = csv.string();
  if (!std::filesystem::is_regular_file(csv)) {
    throw IoError(source, "is missing: --resume needs the curves of the run so far");
  }
  std::istringstream in(read_file(csv));
  const std::size_t parts = model.body.part_names.size();
  std::string header = csv_header(model.body.part_names);
  header.pop_back();  // the newline
  std::string line;
  if (!std::getline(in, line) || line != header) {
    throw InputError(source, "line 1", "is not the header of forensim mummify's curves for this body model");
  }
  // Part water is stored as a percentage; convert back against the initial water of each part.
  const DesiccationTotals start = desiccation_totals(model, initial_desiccation_state(model));
  std::vector<CurveRow> rows;
  while (std::getline(in, line)) {
    const std::string where = "line " + std::to_string(rows.size() + 2);
    std::vector<double> v;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) {
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size() || !std::isfinite(value)) {
        throw InputError(source, where, "'" + cell.substr(0, 40) + "' is not a finite number");
      }
      v.push_back(value);
    }
    if (v.size() != 7 + 3 * parts) throw InputError(source, where, "unexpected number of columns");
    if (v[0] > up_to_day + 1e-9) break;
    CurveRow r;
    r.day = v[0];
    r.totals.water_kg = v[1];
    r.totals.total_kg = v[2];
    r.totals.volume_mm3 = v[3] * 1000.0;
    for (std::size_t p = 0; p < parts; ++p) {
      r.totals.part_water_kg.push_back(v[7 + 3 * p] / 100.0 * start.part_water_kg[p]);
      r.totals.part_total_kg.push_back(v[8 + 3 * p]);
      r.totals.part_volume_mm3.push_back(v[9 + 3 * p] * 1000.0);
    }
    rows.push_back(r);
  }
  require_input(!rows.empty(), source, "", "holds no rows up to the checkpoint's day");
  return rows;
}

}  // namespace

int run_mummify(const MummifyArgs& a) {
  Stopwatch watch;
  JobDocument doc = a.job.empty() ? JobDocument::empty("command line") : JobDocument::load(a.job);
  MummifyJob job = read_mummify_job(doc.root(), a);
  doc.check_all_used();
  check_output_path(a.out, OutputKind::folder);

  BodyModel body;
  // The pictures' titles: the phantom, or the model folder's name.
  std::string label = job.phantom;
  if (!job.model.empty()) {
    label = std::filesystem::path(job.model).lexically_normal().filename().string();
    if (label.empty()) label = std::filesystem::path(job.model).lexically_normal().parent_path().filename().string();
    if (label.empty()) label = "body model";
    body = read_body_model(job.model);
    std::printf("body model %s: %zu nodes, %zu tets\n", job.model.c_str(), body.volume.vertex_count(),
                body.volume.tet_count());
  } else {
    body = make_phantom_model(phantom_model_size(job.phantom, job.size));
    std::printf("%s phantom, size %s: %zu nodes, %zu tets (%s)\n", job.phantom.c_str(), job.size.c_str(),
                body.volume.vertex_count(), body.volume.tet_count(), format_seconds(watch.seconds()).c_str());
  }
  // The output folder is made once the body model has been read: a bad model leaves nothing behind.
  RunFolder run(a.out, "mummify");
  run.timings().add("body model", watch.seconds());
  // Gravity as the body lay (the model's pose unless the job gives it): livor mortis settles along it and the
  // ground lies across it.
  if (!job.skin.gravity_given) job.skin.gravity = body.pose.gravity;
  job.settings.environment.up = -job.skin.gravity;
  const BodyPose pose = body.pose;
  nlohmann::json resolved = doc.resolved();
  resolved["skin"]["gravity"] = {job.skin.gravity.x(), job.skin.gravity.y(), job.skin.gravity.z()};
  run.set_job(resolved);
  const DesiccationModel model = make_desiccation_model(std::move(body), job.settings);
  Stopwatch skin_setup;
  const MummifySkin skin(model.body, job.settings.tissue.initial_moisture, job.skin);
  MummifySkinMotion motion(model.body, job.settings.tissue.initial_moisture, job.skin_motion);
  run.timings().add("skin setup", skin_setup.seconds());
  if (motion.pbd()) {
    const SkinModel& sm = motion.model();
    std::printf(
        "skin motion: position-based, %zu stretch and %zu bending constraints (%zu and %zu colours), r_max %.3f mm "
        "(%.4f of %.0f mm), damping %.2f, %d iterations, %d substeps per shape solve\n",
        sm.stretch.size(), sm.bending.size(), sm.stretch_groups.size(), sm.bending_groups.size(), sm.r_max_mm,
        sm.settings.wrinkle.r_max_relative, sm.model_size_mm, sm.settings.wrinkle.damping, sm.settings.iterations,
        job.skin_motion.substeps);
  } else {
    std::printf("skin motion: glued to the volume (\"pbd\": false)\n");
  }
  // Figure 8's three wrinkle controls on the same drying volume, for comparison (the volume does not depend on
  // the skin, so one run drives all three).
  std::vector<std::unique_ptr<MummifySkinMotion>> figure8;
  if (job.figure8) {
    require_input(motion.pbd(), a.job.empty() ? "command line" : a.job, "figure8",
                  "compares position-based skins; it needs \"pbd\": true");
    for (int set = 0; set < 3; ++set) {
      SkinMotionJob j = job.skin_motion;
      j.wrinkle_set = set;
      j.settings.wrinkle = WrinkleControls::figure8(set);
      figure8.push_back(std::make_unique<MummifySkinMotion>(model.body, job.settings.tissue.initial_moisture, j));
    }
  }
  auto all_checkpoints = [&] {
    std::vector<std::string> skins{motion.checkpoint_bytes()};
    for (const auto& f : figure8) skins.push_back(f->checkpoint_bytes());
    return skins;
  };
  std::printf("skin: %zu vertices, livor blood level %.1f mm above the lowest point (%zu in contact)%s\n",
              model.body.skin.vertex_count(), skin.livor().blood_level_mm - skin.livor().height_min_mm,
              static_cast<std::size_t>(
                  std::count(skin.livor().vertex_contact.begin(), skin.livor().vertex_contact.end(), std::uint8_t{1})),
              skin.has_maps() ? ", baking colour maps" : "");
  const DryingEnvironment& env = job.settings.environment;
  std::printf("environment: %.1f C, %.0f %% RH, wind %.1f m/s -> X_e %.3f kg/kg, h %.3g m/s (air side %.3g m/s)\n",
              env.air_temperature_c, 100.0 * env.relative_humidity, env.air_speed_m_per_s, model.equilibrium_moisture,
              model.transfer_m_per_s, air_mass_transfer_m_per_s(env));

  const double dt = job.step_hours * 3600.0;
  const long long total_steps = std::max<long long>(1, std::llround(job.days * 24.0 / job.step_hours));
  auto frame_of_step = [&](long long step) {  // frame index whose output falls on `step`, or -1
    for (int f = 0; f <= job.frames; ++f)
      if (std::llround(static_cast<double>(total_steps) * f / job.frames) == step) return f;
    return -1;
  };

  const auto checkpoint = run.file("checkpoint.bin");
  DesiccationState state = initial_desiccation_state(model);
  std::vector<CurveRow> rows;
  std::vector<PvdEntry> entries, skin_entries;
  if (a.resume && std::filesystem::exists(checkpoint)) {
    const MummifyCheckpoint saved = read_mummify_checkpoint(checkpoint, model.body.volume.vertex_count());
    state = saved.state;
    require_input(saved.skins.size() == 1 + figure8.size(), checkpoint.string(), "skins",
                  "holds " + std::to_string(saved.skins.size()) + " skin states, the job runs " +
                      std::to_string(1 + figure8.size()) + " (figure8 given on one of the runs only?)");
    motion.restore(saved.skins[0], state, checkpoint.string());
    for (std::size_t k = 0; k < figure8.size(); ++k)
      figure8[k]->restore(saved.skins[k + 1], state, checkpoint.string());
    rows = read_rows(run.file("curves.csv"), model, state.time_s / 86400.0);
    for (const PvdEntry& e : read_pvd(run.file("desiccation.pvd")))
      if (e.time <= state.time_s / 86400.0 + 1e-9) entries.push_back(e);
    if (std::filesystem::exists(run.file("skin.pvd")))
      for (const PvdEntry& e : read_pvd(run.file("skin.pvd")))
        if (e.time <= state.time_s / 86400.0 + 1e-9) skin_entries.push_back(e);
    std::printf("resuming at day %.2f (step %lld of %lld)\n", state.time_s / 86400.0, state.step_count, total_steps);
  }
  PvdSeries series(run.file("desiccation.pvd"), entries);
  run.add_output("desiccation.pvd");
  PvdSeries skin_series(run.file("skin.pvd"), skin_entries);
  run.add_output("skin.pvd");
  double seconds_skin = 0.0, seconds_skin_motion = 0.0;
  long long skin_steps = 0;
  auto write_frames = [&](int frame) {
    write_frame(run, series, model, state, frame);
    Stopwatch skin_watch;
    skin_series.add(state.time_s / 86400.0, skin.write_frame(run.path(), skin.frame(state, motion.positions()), frame));
    seconds_skin += skin_watch.seconds();
  };
  if (rows.empty()) rows.push_back({0.0, desiccation_totals(model, state)});
  if (state.step_count == 0) write_frames(0);

  DesiccationSolver solver(model);
  Progress progress("drying", static_cast<std::size_t>(total_steps));
  progress.set_done(static_cast<std::size_t>(state.step_count));
  double seconds_diffusion = 0.0, seconds_deformation = 0.0;
  std::size_t worst_inverted = 0;
  long long deformation_iterations = 0, deformations = 0, moisture_steps = 0;
  install_interrupt_handler();
  while (state.step_count < total_steps) {
    // The quasi-static shape follows the moisture: solved every `deform_every` steps and at every frame.
    const long long next = state.step_count + 1;
    const bool deform = next % job.deform_every == 0 || frame_of_step(next) >= 0 || next == total_steps;
    // The skin steps with each shape solve, from the previous shape (the positions change only at those).
    std::vector<Vec3> previous_shape;
    if (deform) previous_shape = state.positions;
    const DesiccationStepReport r = solver.step(state, dt, deform);
    if (deform) {
      const SkinMotionReport m = motion.advance(previous_shape, state);
      seconds_skin_motion += m.seconds;
      for (const auto& f : figure8) f->advance(previous_shape, state);
      skin_steps += m.steps;
    }
    deformation_iterations += r.deformation_iterations;
    deformations += deform ? 1 : 0;
    seconds_diffusion += r.seconds_diffusion;
    seconds_deformation += r.seconds_deformation;
    worst_inverted = std::max(worst_inverted, r.inverted_tets);
    ++moisture_steps;
    rows.push_back({state.time_s / 86400.0, desiccation_totals(model, state)});
    progress.advance();
    const int frame = frame_of_step(state.step_count);
    if (frame > 0) {
      write_frames(frame);
      run.write("curves.csv", csv_text(rows, model.body.part_names));
      write_mummify_checkpoint(checkpoint, state, all_checkpoints());
      run.write_record();
    }
    if (interrupt_requested()) {
      write_mummify_checkpoint(checkpoint, state, all_checkpoints());
      run.write("curves.csv", csv_text(rows, model.body.part_names));
      run.write_record();
      throw CancelledError("mummify interrupted at day " + std::to_string(state.time_s / 86400.0) +
                           "; continue with --resume");
    }
  }
  progress.finish();
  run.write("curves.csv", csv_text(rows, model.body.part_names));
  write_mummify_checkpoint(checkpoint, state, all_checkpoints());
  run.add_output("checkpoint.bin");
  if (moisture_steps > 0)
    std::printf(
        "per step: moisture %.3f s; deformation %.3f s (%lld solves, %.1f iterations each)\n",
        seconds_diffusion / static_cast<double>(moisture_steps),
        deformations > 0 ? seconds_deformation / static_cast<double>(deformations) : 0.0, deformations,
        deformations > 0 ? static_cast<double>(deformation_iterations) / static_cast<double>(deformations) : 0.0);
  run.timings().add("moisture steps", seconds_diffusion);
  run.timings().add("deformation steps", seconds_deformation);
  run.timings().add("skin motion", seconds_skin_motion);
  run.timings().add("skin frames", seconds_skin);
  if (skin_steps > 0)
    std::printf("skin: %lld position-based steps, %.1f ms each\n", skin_steps,
                1e3 * seconds_skin_motion / static_cast<double>(skin_steps));
  write_plots(run, rows, model.body.part_names);

  // The skin over time, read back from its frames (so a resumed run writes the same as one run straight through).
  Stopwatch skin_out_watch;
  std::vector<SkinFrame> skin_frames;
  std::vector<std::string> maps;
  for (const PvdEntry& e : skin_series.entries()) {
    skin_frames.push_back(read_skin_frame(run.file(e.file), model.body.skin.vertex_count(), e.time));
    if (skin.has_maps()) {
      std::string map = std::filesystem::path(e.file).replace_extension(".png").generic_string();
      map.replace(map.rfind("frame_"), 6, "colour_");  // skin/frame_NNNN.vtu -> skin/colour_NNNN.png
      maps.push_back(read_file(run.file(map)));
      run.add_output(map);
    }
    run.add_output(e.file);
  }
  write_skin_glb(run.file("skin.glb"), skin.rest_skin(), skin_frames, maps);
  run.add_output("skin.glb");
  run.timings().add("skin GLB", skin_out_watch.seconds());
  const Vec3 fresh = mean_skin_colour(skin.rest_skin(), skin_frames.front());
  const Vec3 dried = mean_skin_colour(skin.rest_skin(), skin_frames.back());
  run.facts()["skin_frames"] = skin_frames.size();
  run.facts()["skin_mean_colour_start"] = {fresh[0], fresh[1], fresh[2]};
  run.facts()["skin_mean_colour_end"] = {dried[0], dried[1], dried[2]};
  const double moisture_end = mean_skin_moisture(skin.rest_skin(), skin_frames.back());
  run.facts()["skin_mean_moisture_end"] = moisture_end;
  // How wrinkled the final skin is: the fine part of its lift-off from the skin glued to the final volume, and
  // the measures of the skin alone (pbd/wrinkle_measure.hpp).
  const std::vector<Vec3> glued = skin_positions_for_frame(model.body, skin_rest_offsets(model.body), state.positions);
  const WrinkleSize wrinkle = wrinkle_size(motion.positions(), glued, model.body.skin.triangles);
  const WrinkleMeasure wrinkles = wrinkle_measure(motion.positions(), model.body.skin.triangles);
  run.facts()["skin_pbd"] = motion.pbd();
  run.facts()["skin_steps"] = motion.step_count();
  run.facts()["skin_wrinkle_height_mm"] = wrinkle.height_mm;
  run.facts()["skin_wrinkle_wavelength_mm"] = wrinkle.wavelength_mm;
  run.facts()["skin_wrinkle_rms_mm"] = wrinkles.rms_smooth_distance_mm;
  run.facts()["skin_mean_abs_curvature_per_mm"] = wrinkles.mean_abs_curvature_per_mm;
  std::printf(
      "skin wrinkles: height %.4f mm over the glued skin (wavelength %.1f mm), RMS from smoothed %.4f mm, mean |H| "
      "%.5f /mm\n",
      wrinkle.height_mm, wrinkle.wavelength_mm, wrinkles.rms_smooth_distance_mm, wrinkles.mean_abs_curvature_per_mm);
  // Does the skin cling to the bones, and is it still a clean surface?
  const std::size_t inverted = inverted_skin_triangles(model.body.skin, motion.positions());
  const std::size_t crossings = skin_self_intersections(model.body.skin, motion.positions());
  run.facts()["skin_inverted_triangles"] = inverted;
  run.facts()["skin_self_intersections"] = crossings;
  const std::vector<double> bone_start =
      part_bone_distance_mm(model.body, model.body.skin.positions, model.body.volume.positions);
  const std::vector<double> bone_end = part_bone_distance_mm(model.body, motion.positions(), state.positions);
  const std::vector<double> bone_glued = part_bone_distance_mm(model.body, glued, state.positions);
  if (!bone_start.empty()) {
    nlohmann::json parts = nlohmann::json::object();
    std::vector<std::size_t> counts(model.body.part_names.size(), 0);
    for (int p : model.body.skin_vertex_parts) ++counts[static_cast<std::size_t>(p)];
    for (std::size_t p = 0; p < bone_start.size(); ++p)
      parts[model.body.part_names[p]] = {{"start_mm", bone_start[p]},
                                         {"end_mm", bone_end[p]},
                                         {"glued_end_mm", bone_glued[p]},
                                         {"skin_vertices", counts[p]}};
    run.facts()["skin_bone_distance"] = parts;
  }
  std::printf("skin: %zu inverted triangles, %zu self-crossings at the end\n", inverted, crossings);
  std::vector<double> figure8_height;
  if (!figure8.empty()) {
    nlohmann::json sets = nlohmann::json::array();
    for (std::size_t k = 0; k < figure8.size(); ++k) {
      const std::vector<Vec3>& x = figure8[k]->positions();
      const WrinkleControls c = WrinkleControls::figure8(static_cast<int>(k));
      const WrinkleMeasure w = wrinkle_measure(x, model.body.skin.triangles);
      const WrinkleSize size = wrinkle_size(x, glued, model.body.skin.triangles);
      figure8_height.push_back(size.height_mm);
      sets.push_back({{"set", k},
                      {"r_max_relative", c.r_max_relative},
                      {"damping", c.damping},
                      {"wrinkle_height_mm", size.height_mm},
                      {"wrinkle_wavelength_mm", size.wavelength_mm},
                      {"wrinkle_rms_mm", w.rms_smooth_distance_mm},
                      {"mean_abs_curvature_per_mm", w.mean_abs_curvature_per_mm},
                      {"inverted_triangles", inverted_skin_triangles(model.body.skin, x)},
                      {"self_intersections", skin_self_intersections(model.body.skin, x)}});
      std::printf(
          "figure 8 set %zu (r_max %.3f, damping %.2f): wrinkle height %.4f mm (wavelength %.1f mm), RMS %.4f mm, "
          "mean |H| %.5f /mm\n",
          k, c.r_max_relative, c.damping, size.height_mm, size.wavelength_mm, w.rms_smooth_distance_mm,
          w.mean_abs_curvature_per_mm);
    }
    run.facts()["figure8"] = sets;
  }
  std::printf(
      "skin: %zu frames in skin.glb; mean moisture ratio %.2f at the end; mean linear colour (%.3f, %.3f, %.3f) -> "
      "(%.3f, %.3f, %.3f)\n",
      skin_frames.size(), moisture_end, fresh[0], fresh[1], fresh[2], dried[0], dried[1], dried[2]);

  const DesiccationTotals& t0 = rows.front().totals;
  const DesiccationTotals& t1 = rows.back().totals;
  std::printf("day %.1f: mass %.1f %%, water %.1f %%, volume %.1f %% of initial; %zu inverted tets\n",
              state.time_s / 86400.0, 100.0 * t1.total_kg / t0.total_kg, 100.0 * t1.water_kg / t0.water_kg,
              100.0 * t1.volume_mm3 / t0.volume_mm3, worst_inverted);
  for (std::size_t p = 0; p < t1.part_water_kg.size(); ++p)
    std::printf("  %-10s water %5.1f %%\n", model.body.part_names[p].c_str(),
                t0.part_water_kg[p] > 0 ? 100.0 * t1.part_water_kg[p] / t0.part_water_kg[p] : 0.0);
  run.facts()["mass_percent"] = 100.0 * t1.total_kg / t0.total_kg;
  run.facts()["water_percent"] = 100.0 * t1.water_kg / t0.water_kg;
  run.facts()["volume_percent"] = 100.0 * t1.volume_mm3 / t0.volume_mm3;
  run.facts()["inverted_tets"] = worst_inverted;
  run.facts()["evaporated_kg"] = state.evaporated_kg;
  run.facts()["water_balance_error_kg"] = t0.water_kg - t1.water_kg - state.evaporated_kg;
  run.facts()["steps"] = total_steps;

  if (!a.no_pictures) {
    Stopwatch picture_watch;
    RenderSettings settings;
    settings.width = settings.height = a.picture_size;
    const DesiccationViews views = desiccation_views(pose.views, ViewAxes{pose.up, pose.front});
    const DesiccationState start = initial_desiccation_state(model);
    std::vector<SheetCell> cells;
    const Image outside = render_moisture(model, state, views, false, settings);
    const Image cut = render_moisture(model, state, views, true, settings);
    const Image shrunk = render_shrinkage(model, state, views, settings);
    write_png(run.file("moisture_outside.png"), outside);
    write_png(run.file("moisture_cut.png"), cut);
    write_png(run.file("shrinkage.png"), shrunk);
    for (const char* f : {"moisture_outside.png", "moisture_cut.png", "shrinkage.png"}) run.add_output(f);
    char caption[80];
    std::snprintf(caption, sizeof caption, "day %.0f", state.time_s / 86400.0);
    cells.push_back({render_moisture(model, start, views, false, settings), "day 0: outside"});
    cells.push_back({outside, std::string(caption) + ": moisture outside"});
    cells.push_back({cut, std::string(caption) + ": moisture, cut through the bone"});
    cells.push_back({shrunk, std::string(caption) + ": shrunken over the original"});
    write_png(run.file("mummify_sheet.png"), make_sheet(cells, 2, "forensim mummify: " + label));
    run.add_output("mummify_sheet.png");
    write_png(run.file("skin_timeline.png"), skin_timeline_sheet(skin.rest_skin(), skin_frames, views.axes,
                                                                 views.outside, settings, label + " skin drying"));
    write_png(run.file("skin_turntable.png"), skin_turntable_sheet(skin.rest_skin(), skin_frames.back(), views.axes, 8,
                                                                   settings, label + ", " + caption));
    for (const char* f : {"skin_timeline.png", "skin_turntable.png"}) run.add_output(f);
    if (!figure8.empty()) {
      // Top row: the three skins as they look; bottom row: a close-up (the wrist and palm when the model has them)
      // of each skin's fine lift-off from the skin glued to the volume (wrinkle_lift_off_mm), on one scale.
      std::vector<SheetCell> sets, lifts;
      std::vector<std::vector<double>> lift_off;
      for (const auto& set : figure8)
        lift_off.push_back(wrinkle_lift_off_mm(set->positions(), glued, model.body.skin.triangles));
      // 2.5 times the largest RMS height: the strongest folds saturate, the pattern stays readable.
      const double range = std::max(2.5 * *std::max_element(figure8_height.begin(), figure8_height.end()), 1e-3);
      BoundingBox close_up;
      for (std::size_t v = 0; v < model.body.skin_vertex_parts.size(); ++v) {
        const std::string& part = model.body.part_names[static_cast<std::size_t>(model.body.skin_vertex_parts[v])];
        if (part == "wrist" || part == "palm") close_up.extend(glued[v]);
      }
      if (close_up.empty()) close_up = bounding_box(glued);
      for (std::size_t k = 0; k < figure8.size(); ++k) {
        SkinFrame f = skin_frames.back();
        f.positions = figure8[k]->positions();
        Scene scene;
        const TriMesh mesh = skin_mesh_of_frame(skin.rest_skin(), f);
        scene.add(mesh, material_from_name("vertex", mesh));
        const WrinkleControls c = WrinkleControls::figure8(static_cast<int>(k));
        char text[96];
        std::snprintf(text, sizeof text, "%.3f, %.2f: %.3f mm", c.r_max_relative, c.damping, figure8_height[k]);
        sets.push_back({render_view(std::move(scene), settings, to_string(views.outside), views.axes), text});
        TriMesh lifted = mesh;
        lifted.vertex_fields.scalars["lift_off_mm"] = lift_off[k];
        Scene field;
        field.add(lifted, SurfaceMaterial::field("lift_off_mm", -range, range, ColormapName::blue_white_red));
        FramingOptions framing;
        framing.axes = views.axes;
        field.environment.up = views.axes.up;
        field.camera = frame_view(close_up, view_from_name(to_string(views.outside)),
                                  static_cast<double>(settings.width) / settings.height, framing);
        lifts.push_back({render(field, settings), "lift-off, close-up"});
      }
      for (SheetCell& cell : lifts) sets.push_back(std::move(cell));
      ColourBar bar;
      bar.colormap = Colormap(ColormapName::blue_white_red);
      bar.min = -range;
      bar.max = range;
      bar.title = "lift-off";
      bar.unit = "mm";
      write_png(run.file("figure8.png"),
                with_colour_bar(make_sheet(sets, 3, label + ", " + caption + ": Figure 8 (r_max, damping)"), bar));
      run.add_output("figure8.png");
    }
    run.timings().add("pictures", picture_watch.seconds());
  }
  run.write_record();
  std::printf("wrote %s (%s)\n", run.path().string().c_str(), format_seconds(watch.seconds()).c_str());
  return 0;
}

namespace {

const RegisterCommand mummify_command{
    "mummify", [](CLI::App& app) {
      auto* sub = app.add_subcommand(
          "mummify", "Desiccation of a body model: moisture diffusion and volume shrinkage over days (FEM)");
      auto a = std::make_shared<MummifyArgs>();
      a->sub = sub;
      sub->add_option("job", a->job, "Job file (JSON); command-line options override its values");
      sub->add_option("--phantom", a->phantom, "Built-in phantom: arm or head")->check(CLI::IsMember({"arm", "head"}));
      sub->add_option("--size", a->size, "Phantom model size: small, paper or fine")
          ->check(CLI::IsMember({"small", "paper", "fine"}));
      sub->add_option("--model", a->model, "Body model folder (forensim tetrahedralize --model) instead of a phantom");
      sub->add_option("--days", a->days, "Simulated days")->check(CLI::Range(0.01, 3650.0));
      sub->add_option("--frames", a->frames, "Output frames (.vtu) after the start")->check(CLI::Range(1, 1000));
      sub->add_option("--step-hours", a->step_hours, "Time step (hours)")->check(CLI::Range(0.01, 240.0));
      sub->add_option("--temperature", a->temperature, "Air temperature (C)")->check(CLI::Range(-40.0, 80.0));
      sub->add_option("--humidity", a->humidity, "Relative humidity (%)")->check(CLI::Range(0.0, 99.0));
      sub->add_option("--wind", a->wind, "Air speed (m/s)")->check(CLI::Range(0.0, 50.0));
      sub->add_option("-o,--out", a->out, "Output folder");
      sub->add_flag("--resume", a->resume, "Continue from the checkpoint in the output folder");
      sub->add_flag("--no-pictures", a->no_pictures, "Skip the renders (curves and plots are still written)");
      sub->add_option("--gravity", a->gravity, "Direction of gravity x y z in the model frame (livor mortis)")
          ->expected(3);
      sub->add_option("--contact-mm", a->contact_mm,
                      "Skin within this distance of the supporting plane is pressure-pale (< 0: no contact)")
          ->check(CLI::Range(-1.0, 1000.0));
      sub->add_option("--map-size", a->map_size, "Texels per side of the baked skin colour maps (0: none)")
          ->check(CLI::Range(0, 8192));
      sub->add_flag("--figure8", a->figure8,
                    "Also step Figure 8's three wrinkle controls on the same volume; compare them in figure8.png and "
                    "the run's facts");
      sub->add_option("--wrinkle-set", a->wrinkle_set,
                      "Figure 8's wrinkle controls: 0 (r_max 0.001, damping 0.5), 1 (0.002, 0.2), 2 (0.004, 0.08)")
          ->check(CLI::Range(0, 2));
      sub->add_option("--picture-size", a->picture_size, "Pixels per picture side")->check(CLI::Range(64, 4096));
      return [a]() { return run_mummify(*a); };
    }};

}  // namespace
}  // namespace forensim::cli
