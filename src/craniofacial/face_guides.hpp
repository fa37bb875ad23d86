#pragma once
/// The nose and mouth rules of Kähler, Haber and Seidel 2003 (section 4.3, Figure 7) as guide values, and the
/// second warp that applies them: from the guides a few skin landmarks of the fitted head get new positions;
/// every other landmark pair keeps its place, and one more RBF warp (eq. 1) moves the fitted skin and muscle
/// grids onto the adjusted landmark set, so only the adjusted regions change.
///
/// Guides are values in the skull's frontal view, as the paper's vertical and horizontal guide lines:
/// coordinates along `lateral` (toward the patient's left) and `up`; `anterior` = lateral x up. Each is
/// optional; a rule whose guides are missing leaves its landmarks alone.
/// - nose width: the alae (al') lie `alar_offset_mm` (5 mm, the Caucasoid rule) lateral of the nasal
///   aperture's widest point on each side;
/// - nose tip (Krogman's rule, via Taylor 2001): pronasale (prn') lies on the extension of the anterior nasal
///   spine (its base and tip marked on the skull), `krogman_factor` (3) spine lengths in front of the
///   mid-philtrum depth marker's tip (the mp pair's target);
/// - mouth width: the cheilia (ch') at the lateral coordinates of the canine / first premolar junctions;
/// - lip height: labrale superius and inferius (ls', li', the lip/skin borders) at the heights of the
///   enamel/root transitions of the upper and lower front teeth; the parting line (ch' and stomion sto') at
///   its guide height, slightly above the blades of the upper incisors.

#include <optional>
#include <string>
#include <vector>

#include "craniofacial/fit_template.hpp"

namespace forensim {

struct FaceGuides {
  Vec3 lateral = Vec3::UnitX();                                           ///< unit: toward the patient's left (LPS +x)
  Vec3 up = Vec3::UnitZ();                                                ///< unit: superior, orthogonal to lateral
  std::optional<double> nasal_aperture_left_mm, nasal_aperture_right_mm;  ///< lateral coordinates
  double alar_offset_mm = 5.0;
  std::optional<Vec3> nasal_spine_base, nasal_spine_tip;  ///< on the skull, mm
  double krogman_factor = 3.0;
  std::optional<double> mouth_corner_left_mm, mouth_corner_right_mm;  ///< lateral coordinates
  std::optional<double> upper_lip_border_mm, lower_lip_border_mm;     ///< up coordinates
  std::optional<double> lip_parting_mm;                               ///< up coordinate
};

struct GuidedHead {
  TriMesh skin;  ///< the fitted skin after the second warp (topology, UVs kept)
  std::vector<MuscleLayout> muscle_layouts;
  std::vector<MuscleShape> muscles;
  std::vector<TemplateSkinLandmark> skin_landmarks;  ///< after the second warp
  std::vector<std::string> adjusted;                 ///< landmarks the guides moved
  std::vector<Vec3> adjusted_from, adjusted_to;      ///< their positions before and after (mm)
  double max_landmark_residual_mm = 0.0;             ///< of the second warp
};

/// Applies `guides` to a fit of `head` (the fit's result must come from this head, with muscles if the
/// result should carry them). Throws InputError for non-finite guides, lateral/up not unit and orthogonal,
/// a nasal spine of zero length or one not pointing forward, or a fit without the landmarks a given rule
/// needs (mp' for the nose tip; ls'/li' for the lip borders).
GuidedHead apply_face_guides(const TemplateHead& head, const TemplateFitResult& fit, const FaceGuides& guides);

}  // namespace forensim
