#include "craniofacial/template_landmark_detection.hpp"

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"

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
  return detect_landmarks(head.skull, template_skull_landmarks(head), template_head_frame(head), skull, options);
}

}  // namespace forensim
