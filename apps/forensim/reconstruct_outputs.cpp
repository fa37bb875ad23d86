// What `forensim reconstruct` and the demo write for a reconstruction: the skin maps, pictures and files of a
// run folder, from the library's in-memory result (reconstruct/reconstruct_face.hpp).

#include "reconstruct_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "craniofacial/landmark_io.hpp"
#include "image/png_io.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/obj_writer.hpp"
#include "phantoms/skin_maps.hpp"
#include "pictures.hpp"
#include "reconstruct/reconstruct_face.hpp"
#include "render/colour_bar.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim::cli {
namespace {

/// The skin maps of the face: the template file's own texture, or procedural maps baked on the template's rest
/// shape (the warp keeps the UVs, so they follow the face). Null without UVs or with texture_size 0.
struct FaceMaps {
  std::shared_ptr<Image> epidermis, normal_map;
};

FaceMaps face_maps(const ReconstructJob& job, const TemplateHead& head) {
  FaceMaps maps;
  if (job.texture_size > 0 && !head.texture_png.empty()) {
    maps.epidermis = std::make_shared<Image>(decode_png(head.texture_png, job.template_file + " texture"));
  } else if (job.texture_size > 0 && head.skin.has_uvs()) {
    SkinMaps baked = make_skin_maps(head.skin, job.texture_size, job.seed);
    maps.epidermis = std::make_shared<Image>(std::move(baked.epidermis));
    maps.normal_map = std::make_shared<Image>(std::move(baked.normal));
  }
  return maps;
}

/// Skin shading, textured with the maps where there are any.
SurfaceMaterial face_material(const FaceMaps& maps) {
  SurfaceMaterial material = SurfaceMaterial::skin();
  if (maps.epidermis) {
    material.colour_source = ColourSource::texture;
    material.base_colour = Vec3f(1, 1, 1);
    material.base_texture = maps.epidermis;
    material.normal_map = maps.normal_map;
  }
  return material;
}

using Pictures = std::vector<std::pair<std::string, std::string>>;  ///< file, PNG bytes

/// The renders: the skin over the skull with the depth vectors (front, side, three-quarter), the textured head,
/// the ensemble's spread and the evaluation's distances where they ran, the sheet of them, the expressions.
Pictures face_pictures(const ReconstructJob& job, const ReconstructedFace& face, const TriMesh& final_skin,
                       const FaceMaps& maps) {
  const ReconstructInputs& in = face.inputs;
  const Skull& skull = in.skull;
  const ReconstructionResult& result = face.reconstruction->result();
  // "auto": the detected head frame (superior up, the face to the front) where landmarks were detected.
  ViewAxes axes = axes_from_name(job.axes == "auto" ? "lps" : job.axes);
  if (job.axes == "auto" && in.detection)
    axes = ViewAxes{in.detection->frame.axes.col(2), -in.detection->frame.axes.col(1)};
  Pictures pictures;
  RenderSettings settings;
  settings.width = settings.height = job.picture_size;
  settings.samples_per_pixel = job.samples;
  settings.seed = job.seed;
  auto skin_ptr = std::make_shared<const TriMesh>(final_skin);
  auto skull_ptr = std::make_shared<const TriMesh>(skull.mesh);
  Scene overlay = skin_over_bone_scene(skin_ptr, skull_ptr, 0.35, axes);
  std::vector<std::pair<Vec3, Vec3>> depth_lines;
  for (const DepthVector& v : result.depth_vectors.vectors) depth_lines.emplace_back(v.bone_mm, v.skin_mm);
  add_depth_vectors(overlay, depth_lines);
  std::vector<SheetCell> cells;
  for (const auto& [view, caption] : std::vector<std::pair<std::string, std::string>>{
           {"front", "front"}, {"left", "side"}, {"three_quarter", "three-quarter"}}) {
    Image image = render_view(overlay, settings, view, axes);
    pictures.emplace_back("render_" + (view == "left" ? std::string("side") : view) + ".png", encode_png(image));
    cells.push_back({std::move(image), caption});
  }
  Scene textured_face;
  textured_face.environment.up = axes.up;
  const SurfaceMaterial skin_material = face_material(maps);
  textured_face.add(skin_ptr, skin_material, "skin");
  Image textured = render_view(textured_face, settings, "three_quarter", axes);
  pictures.emplace_back("render_textured.png", encode_png(textured));
  cells.push_back({std::move(textured), "reconstructed head"});
  if (face.uncertainty) {
    // The spread over the reconstructed face, with its scale.
    Scene spread;
    spread.environment.up = axes.up;
    const double top = std::max(face.uncertainty->max_spread_mm, 1e-3);
    spread.add(skin_ptr, SurfaceMaterial::field("uncertainty", 0.0, top, ColormapName::inferno), "spread");
    ColourBar bar;
    bar.colormap = Colormap{ColormapName::inferno};
    bar.max = top;
    bar.title = "spread";
    bar.unit = "mm";
    Image map = with_colour_bar(render_view(spread, settings, "three_quarter", axes), bar);
    pictures.emplace_back("render_uncertainty.png", encode_png(map));
    cells.push_back({std::move(map), "uncertainty (" + std::to_string(face.uncertainty->samples) + " samples)"});
  }
  if (face.evaluation) {
    // The real face coloured by its signed distance from the reconstruction, front and side, with the scale.
    Scene heat;
    heat.environment.up = axes.up;
    const double range = std::max(5.0, std::ceil(face.evaluation->p90_abs_mm));
    heat.add(std::make_shared<const TriMesh>(face.evaluation->face),
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
  if (!face.expressions.empty()) {
    // The expressions sheet: the neutral face, then each preset, from the front.
    std::vector<SheetCell> expression_cells;
    auto render_face = [&](std::shared_ptr<const TriMesh> mesh) {
      Scene scene;
      scene.environment.up = axes.up;
      scene.add(std::move(mesh), skin_material, "skin");
      return render_view(scene, settings, "front", axes);
    };
    expression_cells.push_back({render_face(skin_ptr), "neutral"});
    for (const MorphTarget& target : face.expressions) {
      auto posed = std::make_shared<TriMesh>(final_skin);
      for (std::size_t v = 0; v < posed->positions.size(); ++v) posed->positions[v] += target.position_deltas[v];
      expression_cells.push_back({render_face(posed), target.name});
    }
    pictures.emplace_back("expressions.png",
                          encode_png(make_sheet(expression_cells, 4, "forensim reconstruct: expressions")));
  }
  return pictures;
}

/// The run folder's files.
void write_face_files(RunFolder& run, const ReconstructedFace& face, const TriMesh& final_skin, const FaceMaps& maps,
                      const Pictures& pictures, const nlohmann::json& provenance) {
  const ReconstructInputs& in = face.inputs;
  const ReconstructionResult& result = face.reconstruction->result();
  const std::shared_ptr<Image>& epidermis = maps.epidermis;
  const std::shared_ptr<Image>& normal_map = maps.normal_map;
  LandmarkSet skull_set("skull");
  for (const DepthVector& v : result.depth_vectors.vectors)
    skull_set.add({v.bone_landmark, v.bone_mm, v.source, v.confidence});
  LandmarkSet skin_set = result.skin_landmarks;
  skin_set.set_name("skin");
  GltfScene scene;
  GltfMeshNode head_node;
  head_node.name = "head";
  head_node.mesh = final_skin;
  head_node.morph_targets = face.expressions;
  if (epidermis) {
    head_node.textures.base_color_png = encode_png(*epidermis);
    if (normal_map) head_node.textures.normal_png = encode_png(*normal_map);
  }
  scene.nodes.push_back(std::move(head_node));
  scene.nodes.push_back(skull_gltf_node("skull", in.skull.mesh));
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
  write_obj(run.file("skull.obj"), in.skull.mesh);
  run.add_output("skull.obj");
  run.add_output("skull.mtl");
  write_landmarks(run.file("skull_landmarks.mrk.json"), skull_set);
  run.add_output("skull_landmarks.mrk.json");
  write_landmarks(run.file("skin_landmarks.mrk.json"), skin_set);
  run.add_output("skin_landmarks.mrk.json");
  if (face.uncertainty) {
    nlohmann::json u = {{"samples", face.uncertainty->samples},
                        {"seed", face.uncertainty->seed},
                        {"method",
                         "depths drawn from the table's means and SDs; spread = RMS distance of the members' "
                         "vertex positions from their mean, per head.obj vertex"},
                        {"max_spread_mm", face.uncertainty->max_spread_mm},
                        {"mean_spread_mm", face.uncertainty->mean_spread_mm},
                        {"vertex_spread_mm", face.uncertainty->vertex_spread_mm}};
    run.write("uncertainty.json", u.dump());
    // The head with its "uncertainty" vertex field (mm), for ParaView and forensim serve's viewer.
    write_vtu(run.file("head_uncertainty.vtu"), final_skin);
    run.add_output("head_uncertainty.vtu");
  }
  if (face.evaluation) {
    run.write("evaluation.json", face.evaluation_record.dump(2));
    // The measured real face with its "distance" vertex field (mm), for ParaView and the viewer.
    write_vtu(run.file("evaluation_face.vtu"), face.evaluation->face);
    run.add_output("evaluation_face.vtu");
  }
  for (const auto& [file, bytes] : pictures) run.write(file, bytes);
  run.write("violations.json", face.reconstruction->violations_json().dump(2));
  run.write("provenance.json", provenance.dump(2));
}

/// The run's figures for run.json and the command's summary line.
void record_facts(RunFolder& run, const ReconstructedFace& face) {
  const ReconstructionResult& result = face.reconstruction->result();
  const TemplateFitResult& fit = face.reconstruction->fit();
  run.facts()["given_pairs"] = fit.given_pair_count;
  run.facts()["interpolated_pairs"] = fit.interpolated.names.size();
  run.facts()["correction_pairs"] = fit.corrections.sources.size();
  run.facts()["violations_before"] = result.violations_given_only.total();
  run.facts()["violations_after"] = result.violations_final.total();
  run.facts()["expressions"] = face.expressions.size();
  if (face.evaluation) {
    run.facts()["evaluation_mean_abs_mm"] = face.evaluation->mean_abs_mm;
    run.facts()["evaluation_rms_mm"] = face.evaluation->rms_mm;
    run.facts()["evaluation_signed_mean_mm"] = face.evaluation->signed_mean_mm;
    run.facts()["evaluation_within_percent"] = 100.0 * face.evaluation->within_share;
  }
}

}  // namespace

nlohmann::json run_reconstruction(const ReconstructJob& job, const std::filesystem::path& out,
                                  const nlohmann::json& resolved_job, const nlohmann::json& guides_record) {
  Stopwatch total;
  ReconstructedFace face = reconstruct_face(job);
  for (const std::string& line : face.inputs.messages) std::printf("%s\n", line.c_str());
  Timings timings = face.timings;
  Stopwatch watch;
  TriMesh& final_skin = face.skin;
  final_skin.material.name = "skin";
  const FaceMaps maps = face_maps(job, *face.inputs.head);
  if (maps.epidermis) timings.add("skin maps", watch.lap());
  Pictures pictures;
  if (job.picture_size > 0) {
    pictures = face_pictures(job, face, final_skin, maps);
    timings.add("renders", watch.lap());
  }
  const nlohmann::json provenance = reconstruction_provenance(job, face, guides_record);

  RunFolder run(out, "reconstruct");
  run.set_job(resolved_job);
  run.set_seed(job.seed);
  write_face_files(run, face, final_skin, maps, pictures, provenance);
  timings.add("write", watch.lap());
  for (const auto& [stage, seconds] : timings.stages()) run.timings().add(stage, seconds);
  record_facts(run, face);
  run.facts()["seconds_total"] = total.seconds();
  run.write_record();
  return run.facts();
}

}  // namespace forensim::cli
