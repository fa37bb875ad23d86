#pragma once
// One coarse template head per test program (building it takes a few seconds).
#include "craniofacial/interpolated_landmarks.hpp"
#include "craniofacial/template_head.hpp"

namespace forensim::test {

inline const TemplateHead& coarse_template_head() {
  static const TemplateHead head = make_template_head(template_head_options("coarse"));
  return head;
}

/// The template's own landmarks as fit input: skull positions and depth vectors skin - skull.
inline LandmarkDepths template_landmark_depths(const TemplateHead& head) {
  LandmarkDepths d;
  for (const TemplateLandmarkPair& p : head.landmarks) {
    d.names.push_back(p.skin_name);
    d.skull.push_back(p.skull);
    d.depth_vectors.push_back(p.skin - p.skull);
  }
  return d;
}

}  // namespace forensim::test
