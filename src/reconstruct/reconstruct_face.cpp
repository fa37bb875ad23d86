#include "reconstruct/reconstruct_face.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>

#include "craniofacial/face_expression.hpp"
#include "craniofacial/head_frame.hpp"

namespace forensim {
namespace {

/// The CT's real face (its skin iso-surface) against the reconstruction over the face region.
void evaluate(const ReconstructInputs& in, ReconstructedFace& face) {
  const ReconstructionResult& result = face.reconstruction->result();
  double skin_iso = 0.0;
  const TriMesh real_skin = real_face_surface(*in.volume, in.skull.source, {}, &skin_iso);
  // The frame of the region: detected, the template's (its own landmarks), or from the file's Frankfort landmarks.
  const HeadFrame frame = in.known_frame ? *in.known_frame : head_frame_from_skull(in.skull.mesh, in.landmarks);
  LandmarkSet used("skull");
  for (const DepthVector& v : result.depth_vectors.vectors) used.add({v.bone_landmark, v.bone_mm, v.source, 1.0});
  const FaceRegionOptions region_options;
  const FaceRegion region = face_region(used, frame, region_options);
  face.evaluation = evaluate_face(real_skin, result.skin, region, in.skull.field_of_view);
  nlohmann::json& record = face.evaluation_record;
  record = face.evaluation->to_json();
  record["real_face"] = {{"source", in.skull.source},
                         {"skin_iso", skin_iso},
                         {"triangles", real_skin.triangle_count()},
                         {"measured_triangles", face.evaluation->face.triangle_count()}};
  record["region"] = {
      {"definition",
       "in front of the coronal plane through the gonia, below the Frankfort-parallel plane " +
           fmt::format("{:g}", region_options.forehead_mm) +
           " mm above glabella, above the mandibular plane (menton, gonia) lowered by " +
           fmt::format("{:g}", region_options.chin_margin_mm) +
           " mm; exterior skin only (a ray along the normal leaves the head), the scan's cut caps left out"},
      {"frame", in.detection                     ? "detected head frame"
                : in.landmark_mode == "template" ? "template head frame"
                                                 : "head frame of the landmark file (Frankfort, midsagittal)"}};
  record["method"] =
      "signed distance from each real-face vertex to the closest point of the reconstructed skin (positive: "
      "the real face outside the reconstruction), weighted by a third of its triangles' area";
  record["literature_within_2_5mm_percent"] = {54, 77};
}

/// The head frame automatic landmarks were refined in: origin and axes in the skull's coordinates (mm).
nlohmann::json head_frame_json(const HeadFrame& frame) {
  const auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  return {{"origin_mm", vec(frame.origin)},
          {"x_left", vec(frame.axes.col(0))},
          {"y_posterior", vec(frame.axes.col(1))},
          {"z_superior", vec(frame.axes.col(2))},
          {"perpendicularity_deg", frame.perpendicularity_deg}};
}

/// The detection's record: the registration's figures, each landmark's rule and scores, those left out.
nlohmann::json detection_json(const LandmarkDetection& detection) {
  nlohmann::json details = nlohmann::json::array();
  for (const DetectedLandmark& d : detection.details) {
    details.push_back({{"name", d.name},
                       {"rule", to_string(d.rule)},
                       {"confidence", d.confidence},
                       {"residual_mm", d.residual_mm},
                       {"sharpness", d.sharpness},
                       {"symmetry_error_mm", d.symmetry_error_mm},
                       {"refinement_mm", (d.refined_mm - d.transferred_mm).norm()},
                       {"transferred_mm", {d.transferred_mm.x(), d.transferred_mm.y(), d.transferred_mm.z()}},
                       {"in_view", d.in_view}});
  }
  const SkullRegistration& reg = detection.registration;
  nlohmann::json record = {{"reference", "template skull"},
                           {"similarity_scale", reg.similarity.scale},
                           {"similarity_rms_mm", reg.similarity_rms_mm},
                           {"non_rigid_rms_mm", reg.rms_mm},
                           {"head_frame", head_frame_json(detection.frame)},
                           {"landmarks", details}};
  nlohmann::json left_out = nlohmann::json::array();
  for (const auto& [name, reason] : detection.left_out) left_out.push_back({{"name", name}, {"reason", reason}});
  record["left_out"] = left_out;
  return record;
}

}  // namespace

ReconstructedFace reconstruct_face(const ReconstructJob& job) {
  ReconstructedFace face;
  face.inputs = prepare_reconstruction(job);
  const ReconstructInputs& in = face.inputs;
  face.timings = in.timings;
  Stopwatch watch;
  face.reconstruction =
      std::make_unique<Reconstruction>(*in.fitted, in.skull.mesh, in.landmarks, in.depths, in.options);
  face.skin = face.reconstruction->result().skin;
  face.timings.add("reconstruction", watch.lap());

  if (job.uncertainty_samples > 0) {
    face.uncertainty = reconstruction_uncertainty(*face.reconstruction, job.uncertainty_samples,
                                                  job.uncertainty_seed.value_or(job.seed));
    face.skin.vertex_fields.scalars["uncertainty"] = face.uncertainty->vertex_spread_mm;
    face.timings.add("uncertainty", watch.lap());
  }
  if (job.evaluate) {
    evaluate(in, face);
    face.timings.add("evaluation", watch.lap());
  }
  // Expressions (paper section 5): the muscles contracted under the reconstructed skin, over the target skull;
  // each preset becomes a morph target of the head.
  if (!job.expressions.empty()) {
    const ReconstructionResult& result = face.reconstruction->result();
    face.expressions = expression_morph_targets(result.skin, in.skull.mesh, result.muscles, job.expressions);
    face.timings.add("expressions", watch.lap());
  }
  return face;
}

nlohmann::json reconstruction_provenance(const ReconstructJob& job, const ReconstructedFace& face,
                                         const nlohmann::json& guides_record) {
  const ReconstructInputs& in = face.inputs;
  const TemplateHead& head = *in.head;
  nlohmann::json provenance;
  provenance["template"] = {{"name", in.template_from_file ? job.template_file : "built-in head phantom template"},
                            {"source", in.fitted->source},
                            {"carried_onto_skull", in.carried},
                            {"detail", in.template_from_file ? "file" : job.template_detail},
                            {"landmark_reference", in.template_from_file && in.detection
                                                       ? "built-in template skull (" + job.template_detail + ")"
                                                       : std::string("the template's skull")},
                            {"own_texture", !head.texture_png.empty()},
                            {"skin_triangles", head.skin.triangle_count()},
                            {"landmark_pairs", head.landmarks.size()},
                            {"muscles", head.muscles.size()},
                            {"uv_atlas", head.skin.has_uvs()}};
  const Skull& skull = in.skull;
  provenance["skull"] = {{"source", skull.source},
                         {"kind", skull.kind.empty() ? "mesh" : skull.kind},
                         {"triangles", skull.mesh.triangle_count()},
                         {"notes", skull.notes}};
  if (skull.iso_value) provenance["skull"]["bone_iso"] = *skull.iso_value;
  if (skull.seed_iso_value) {
    provenance["skull"]["bone_threshold"] = {
        {"method", "half-maximum height (Spoor et al. 1993; Coleman and Colbert 2007)"},
        {"seed_iso", *skull.seed_iso_value},
        {"profiles", skull.threshold_profiles}};
  }
  provenance["table"] = {{"name", in.table.name},
                         {"origin", in.table.origin},
                         {"source", in.table.comments},
                         {"group", in.depths.group.describe()},
                         {"variant", in.depths.variant},
                         {"notes", in.depths.notes},
                         {"build", job.build.empty() ? "as the group" : job.build}};
  if (!in.build_method.empty()) provenance["table"]["build_method"] = in.build_method;
  const nlohmann::json record = face.reconstruction->provenance();
  provenance["landmarks"] = record["landmarks"];
  provenance["landmarks"]["origin"] = in.landmark_origin;
  if (in.detection) provenance["landmarks"]["detection"] = detection_json(*in.detection);
  provenance["guides"] = guides_record;
  if (job.measure_guides) provenance["guides_measured"] = in.measured_guides;
  if (in.options.guides) provenance["guides_adjusted"] = record["guides_adjusted"];
  if (!face.expressions.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const MorphTarget& target : face.expressions) {
      double largest = 0.0;
      for (const Vec3& d : target.position_deltas) largest = std::max(largest, d.norm());
      list.push_back({{"name", target.name}, {"max_displacement_mm", largest}});
    }
    provenance["expressions"] = {
        {"model", "skin-muscle-skull springs with linear and sphincter muscles (paper section 5)"},
        {"morph_targets", list}};
  }
  if (face.uncertainty)
    provenance["uncertainty"] = {{"samples", face.uncertainty->samples}, {"seed", face.uncertainty->seed}};
  if (face.evaluation) provenance["evaluation"] = face.evaluation_record;
  provenance["seed"] = job.seed;
  return provenance;
}

}  // namespace forensim
