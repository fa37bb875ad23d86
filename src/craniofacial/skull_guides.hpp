#pragma once
/// The nose and mouth guides of section 4.3 (Kähler, Haber and Seidel 2003, Figure 7) measured on the skull,
/// where its shape and landmarks allow, so a reconstruction applies the rules without a user placing the guide
/// lines by hand; guide values a user gives override the measured ones (merge_face_guides).
///
/// What is measured (head directions: `lateral` toward the patient's left, `up` superior, anterior =
/// lateral x up; from the Frankfort/midsagittal head frame when the landmarks give it, else LPS axes):
/// - nasal aperture: rays cast from in front of the face toward the back on horizontal lines between the
///   nasal spine (ans, else subspinale ss) and rhinion (rhi), or nasion (n) when no line below rhinion opens
///   or rhinion is missing (a scan too coarse for the thin nasal bones puts rhinion on the maxilla below the
///   opening). Inside the aperture the first
///   hit lies deep (the nasal cavity); on the maxilla beside it, shallow. On each line the aperture's
///   lateral edges are where the hit depth, going outward, comes within `edge_level` (a quarter) of the
///   step between the shallowest depth within `lateral_reference_mm` on that side (the front of the bone
///   beside the aperture) and the depth at the midline: the rim, where the bone turns into the opening;
///   the line of greatest width in the lowest run of lines that open gives nasal_aperture_left/right_mm
///   (lines whose midline is less than `min_aperture_depth_mm` deeper than the sides are not an opening;
///   depths are capped `aperture_depth_cap_mm` behind the line's front, since a ray through the aperture may
///   meet the back of the skull);
/// - nasal spine (Krogman's rule): its tip is ans; its base lies on the spine's axis (the anterior
///   direction) at the coronal depth of subspinale, so the spine's length is how far ans stands in front of
///   point A; needs ans and ss;
/// - mouth corners: at the canine / first premolar junctions, half a canine crown width
///   (`canine_half_width_mm`, 3.75 mm: the mean mesiodistal width of an upper canine is about 7.5 mm) lateral
///   of the canine eminences: at the height of the supra-canine points sC_L / sC_R, where the upper alveolar
///   arch turns from facing forward to facing sideways (the point furthest along (lateral + anterior) / sqrt 2
///   among the vertices within `canine_band_mm` of that height, on that side, at most `canine_depth_mm` behind
///   the arch's front, whose normal faces that way); sC_L / sC_R themselves where no eminence is found (the
///   reference's supra-canine points need not lie over the canines: the template's arch is narrow).
/// Lip borders and the parting line (enamel/root transitions, incisor blades) are not measured: they stay
/// guide values for the user.

#include <optional>
#include <string>
#include <vector>

#include "craniofacial/face_guides.hpp"
#include "craniofacial/head_frame.hpp"
#include "craniofacial/landmark_set.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct SkullGuideOptions {
  double min_aperture_depth_mm = 4.0;   ///< least depth step that counts as the aperture's opening
  double lateral_reference_mm = 28.0;   ///< how far beside the midline the maxilla's front is sought
  double aperture_depth_cap_mm = 30.0;  ///< hits deeper than this behind the face's front count as this deep
  double edge_level = 0.25;             ///< share of the depth step (from the bone's front) at the rim
  double sample_step_mm = 0.5;          ///< spacing of the rays along each line
  double line_step_mm = 1.0;            ///< spacing of the horizontal lines
  double canine_half_width_mm = 3.75;
  double canine_band_mm = 4.0;    ///< half-height of the band about the supra-canine points searched
  double canine_depth_mm = 25.0;  ///< how far behind the arch's front the eminence may lie
};

struct SkullGuideMeasurement {
  FaceGuides guides;                  ///< lateral/up set; the measured values set, the others empty
  std::vector<std::string> measured;  ///< guide names set ("nasal_aperture", "nasal_spine", "mouth_corners")
  std::vector<std::string> missing;   ///< "name: why" for each guide that could not be measured
  bool head_frame = false;            ///< directions from a head frame (given or the landmarks'), else LPS
  double aperture_width_mm = 0.0;     ///< of the widest line (0 when not measured)
  double aperture_height_mm = 0.0;    ///< `up` coordinate of that line
  double spine_length_mm = 0.0;       ///< ans in front of subspinale (0 when not measured)
  std::optional<Vec3> canine_left_mm, canine_right_mm;  ///< the canine eminences found (mm), when found
};

/// Measures the guides on `skull` (closed or open mesh, mm, LPS) with its landmarks (canonical names).
/// Throws InputError naming "skull guides" when the skull is empty or an option is not positive; a guide
/// whose landmarks or features are missing is reported in `missing`, not thrown.
/// `frame`, when given (e.g. the frame landmark detection found), sets the head directions; else they come
/// from the landmarks' head frame when it can be made, else LPS axes.
SkullGuideMeasurement measure_skull_guides(const TriMesh& skull, const LandmarkSet& skull_landmarks,
                                           const HeadFrame* frame = nullptr, const SkullGuideOptions& options = {});

/// `measured` with every guide value that `given` sets replacing the measured one (lateral, up and the
/// rule constants from `given` when it sets any value, else from `measured`).
FaceGuides merge_face_guides(const FaceGuides& measured, const FaceGuides& given);

}  // namespace forensim
