#include "craniofacial/template_landmark_detection.hpp"

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {

LandmarkSet template_skull_landmarks(const TemplateHead& head) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  LandmarkSet set("template skull");
  for (const TemplateLandmarkPair& p : head.landmarks) {
    const LandmarkRef skin = vocabulary.resolve(p.skin_name, "template head", p.skin_name);
    const auto bone = vocabulary.paired(skin);
    const std::string name = bone ? vocabulary.name(*bone) : p.bone_name;
    if (set.contains(name)) continue;
    set.add({name, p.skull, LandmarkSource::detected, 1.0});
  }
  return set;
}

HeadFrame template_head_frame(const TemplateHead& head) {
  require_input(!head.skull.positions.empty(), "template head", "skull", "has no vertices");
  HeadFrame frame;
  frame.midsagittal = Plane{Vec3::Zero(), Vec3::UnitX()};
  frame.origin = frame.midsagittal.project(bounding_box(head.skull.positions).center());
  frame.frankfort = Plane{frame.origin, Vec3::UnitZ()};
  frame.axes = Mat3::Identity();
  return frame;
}

LandmarkDetection detect_template_landmarks(const TemplateHead& head, const TriMesh& skull,
                                            const LandmarkDetectionOptions& options) {
  require_input(!skull.triangles.empty(), "target skull", "", "has no triangles");
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const LandmarkSet reference = template_skull_landmarks(head);
  const HeadFrame frame = template_head_frame(head);
  LandmarkDetection detection = detect_landmarks(head.skull, reference, frame, skull, options);
  const Similarity& similarity = detection.registration.similarity;
  TriMesh target = skull;
  if (target.normals.size() != target.positions.size()) compute_normals(target);
  TriMesh template_skull = head.skull;
  if (template_skull.normals.size() != template_skull.positions.size()) compute_normals(template_skull);
  const ClosestPointQuery surface(target);
  LandmarkSet landmarks(detection.landmarks.name());
  for (std::size_t i = 0; i < detection.landmarks.size(); ++i) {
    Landmark l = detection.landmarks[i];
    DetectedLandmark& detail = detection.details[i];
    Vec3 position = detail.transferred_mm;
    const auto definition = landmark_definition(l.name);
    if (!detail.in_view) {
      // Not seen by the scan: on the registered template (complete_skull puts its missing part there).
      detail.refined_mm = position;
      landmarks.add(std::move(l));
      continue;
    }
    if (definition && definition->rule != LandmarkRule::transfer) {
      // The definition's point on the template skull and on the target; the template's landmark lies `offset`
      // from the former. Where either is no local extremum the registration alone places the landmark.
      const Side side = vocabulary.resolve(l.name, "template landmarks", l.name).side;
      const Vec3 known = reference.at(l.name).position_mm;
      const RefinedLandmark on_reference = refine_landmark(template_skull, frame, *definition, side, known);
      const RefinedLandmark on_target =
          refine_landmark(target, detection.frame, *definition, side, detail.transferred_mm);
      if (!on_reference.at_search_limit && !on_target.at_search_limit) {
        position =
            on_target.position_mm + similarity.scale * (similarity.rotation * (known - on_reference.position_mm));
      }
    }
    const auto hit = surface.query(position);
    l.position_mm = hit ? hit->point : position;
    detail.refined_mm = l.position_mm;
    landmarks.add(std::move(l));
  }
  detection.landmarks = std::move(landmarks);
  return detection;
}

ScanLandmarkDetection detect_scan_landmarks(const TemplateHead& head, const TriMesh& skull,
                                            const ScanFieldOfView& view) {
  ScanLandmarkDetection out;
  LandmarkDetectionOptions options;
  options.registration.similarity.target_view = view;
  out.detection = detect_template_landmarks(head, skull, options);
  for (const DetectedLandmark& d : out.detection.details) out.unseen += d.in_view ? 0 : 1;
  if (out.unseen > 0) out.completion = complete_skull(skull, view, head.skull, out.detection.registration);
  return out;
}

}  // namespace forensim
