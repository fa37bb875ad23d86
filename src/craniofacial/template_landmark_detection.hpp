#pragma once
/// Automatic landmarks with the template head as the reference skull (issue 8, paper section 3: landmarks are
/// placed on the skull before the template is fitted): the template's own skull landmarks, found on the
/// phantom's bone by their definitions (template_head.hpp), are carried onto a target skull by
/// detect_landmarks (registration, then refinement by each landmark's definition in the target's head frame,
/// with a confidence per landmark). The template has no porion or orbitale, so its head frame is given
/// directly: the phantom's LPS axes with the midsagittal plane x = 0.

#include <cstddef>
#include <optional>

#include "craniofacial/landmark_detection.hpp"
#include "craniofacial/skull_completion.hpp"
#include "craniofacial/template_head.hpp"

namespace forensim {

/// The template's skull landmarks as a set, named by the vocabulary's bone landmark of each pair's skin
/// landmark (the template names the upper and lower second-molar points both "ecm2"; the vocabulary keeps the
/// lower one apart as "ecm2i"), source detected (they were located by their definitions), confidence 1.
LandmarkSet template_skull_landmarks(const TemplateHead& head);

/// The template's head frame: identity axes (LPS: x the patient's left, y posterior, z superior), the
/// midsagittal plane x = 0, the origin at the skull's bounding-box centre moved onto that plane, the
/// Frankfort plane z = origin.z.
HeadFrame template_head_frame(const TemplateHead& head);

/// Landmarks on `skull` (mm, any pose; outward triangles) by detect_landmarks with the template's skull, its
/// landmarks and its frame as the reference. The template's landmarks follow the template's definitions
/// (template_head.hpp), which place some sites a few mm from where detection's definitions (refine_landmark)
/// do, so each landmark is placed as follows: a transfer site stays where the registration put it; an
/// extremal or midline site is refined on the target and moved by the offset from the definition's point to
/// the template's landmark measured on the template skull (carried through the similarity), unless either
/// refinement ends at its search limit (no local extremum: the registration alone places it); then it goes onto
/// the skull's surface (closest point). The template's own skull thus detects its own landmarks. A landmark
/// outside the target's field of view (options.registration.similarity.target_view) stays at its transferred
/// position, on the registered template (see skull_completion.hpp). Result
/// landmarks have source detected and detect_landmarks' confidence in [0, 1]; details[i].refined_mm is the
/// final position. Throws InputError for an empty skull and the registration's errors.
LandmarkDetection detect_template_landmarks(const TemplateHead& head, const TriMesh& skull,
                                            const LandmarkDetectionOptions& options = {});

/// Automatic landmarks as forensim reconstruct places them on a scan: detect_template_landmarks within the scan's
/// field of view, then, where landmarks lie outside it, the skull completed with the registered template's
/// missing part (complete_skull).
struct ScanLandmarkDetection {
  LandmarkDetection detection;
  std::size_t unseen = 0;                     ///< landmarks outside the field of view
  std::optional<SkullCompletion> completion;  ///< when unseen > 0
};
ScanLandmarkDetection detect_scan_landmarks(const TemplateHead& head, const TriMesh& skull,
                                            const ScanFieldOfView& view);

}  // namespace forensim
