#pragma once
/// A template head made from a real head (`forensim template build`): the user's head mesh (a surface scan, with
/// its texture) or a CT (its skin, its skull and the skull's landmarks) becomes the template the reconstruction
/// warps (Kähler, Haber and Seidel 2003, section 4.1: "a generic head model ... with landmarks, muscles and a
/// texture").
///
/// The built-in template is carried onto the subject, so the new template keeps its topology, UV atlas, charts and
/// muscle layout, and only takes the subject's shape:
/// 1. Correspondences. With a skull and its landmarks (a CT): each template pair's skull landmark s' on the
///    subject's skull, its direction n' (the skull normal averaged over a patch, skull_normals.hpp) and the
///    subject's skin point q' where s' + t n' first meets the subject's skin (t <= max_depth_mm). Skin landmarks
///    given on the subject's skin (a head mesh: placed in 3D Slicer, or transferred by registration) are taken
///    as they are. Where the scan did not hold the skin (a CT's vault above its first slice), the target is the
///    template's own depth along the subject's normal.
/// 2. The subject is placed in the template's frame (the rigid fit of those skin points; it keeps its size), and
///    the biharmonic RBF warp of eq. 1 from the template's skin points onto the subject's carries the template's
///    skin, skin landmarks and muscle grids. Skin points only: a skull point a few mm under a skin point with
///    another displacement would bend the warp between them.
/// 3. The warped skin moves onto the subject's in rounds: each vertex along its normal to the nearest hit either
///    way within conform_reach_mm whose surface faces the same way (not a CT's cut cap nor the rim at the cut; a
///    hit disagreeing with most of its neighbours' by more than 3 mm is dropped); the shifts of the vertices
///    without a hit (the vault a CT did not scan, folds) are filled in from their neighbours' (a harmonic
///    extension), so the skin stays whole. Triangles still turned over take their neighbours' mean.
/// 4. The skull: the subject's, or without one (a head mesh) the template's placed under the new skin at the
///    template's own tissue depths (each pair's skull point at its skin point less its depth along the carried
///    normal, by a second warp on those points). Each pair's skin point is where s' + t n' meets the new skin,
///    its depth t (the subject's own depths with a CT); skin-only landmarks and muscle grids move to their
///    closest points on the new skin.
/// 5. A head mesh's texture is baked onto the template's atlas: each texel's point of the new skin looks up the
///    closest point of the subject's mesh and samples its texture there.

#include <optional>
#include <string>
#include <vector>

#include "craniofacial/landmark_set.hpp"
#include "craniofacial/scan_field_of_view.hpp"
#include "craniofacial/template_head.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"

namespace forensim {

/// What a template is built from. Lengths in mm, in the subject's own frame.
struct TemplateBuildInput {
  std::string source;         ///< the files it came from, recorded as TemplateHead::source
  TriMesh skin;               ///< the subject's skin: a CT's skin iso-surface, or a head mesh (with UVs for a texture)
  ScanFieldOfView skin_view;  ///< a CT's lattice: hits on the skin's cut caps are not the face
  std::optional<TriMesh> skull;  ///< the subject's skull (a CT's bone), or none: the template's follows the warp
  LandmarkSet skull_landmarks;   ///< bone landmarks on `skull` (detected or a file), canonical names
  LandmarkSet skin_landmarks;    ///< skin landmarks on `skin` ("se'", "prn'", ...), canonical names
  Image texture;                 ///< the head mesh's base-colour map (on skin's UVs), or empty
};

struct TemplateBuildOptions {
  double max_depth_mm = 60.0;      ///< longest skull-to-skin ray of a pair on the subject
  double conform_reach_mm = 15.0;  ///< farthest a warped skin vertex moves onto the subject's skin
  double patch_radius_mm = 5.0;    ///< skull normals averaged over this patch
  int texture_size = 1024;         ///< baked texture, texels per side
};

/// What the build did, for the run record.
struct TemplateBuildReport {
  std::vector<std::string> pairs_from_skull;  ///< skin names of pairs measured on the subject's skull
  std::vector<std::string> pairs_from_skin;   ///< skin names of pairs given on the subject's skin
  /// Pairs whose skin the scan did not hold (a CT's vault): the template's own depth along the subject's normal.
  std::vector<std::string> pairs_unscanned;
  std::vector<std::pair<std::string, std::string>> pairs_left;  ///< pairs that kept the warp (name, why)
  std::size_t warp_landmarks = 0;                               ///< correspondences of the warp
  std::size_t vertices_conformed = 0;                           ///< skin vertices moved onto the subject's skin
  std::size_t vertices_warped = 0;    ///< skin vertices with no hit (kept where the warp put them)
  double mean_conform_mm = 0.0;       ///< mean distance a conformed vertex moved
  std::size_t flipped_triangles = 0;  ///< skin triangles whose normal turned against the warped skin's
  bool texture_baked = false;
  bool skull_at_template_depths = false;  ///< no skull given: the template's placed at its own depths under the skin
};

struct TemplateBuild {
  TemplateHead head;
  TemplateBuildReport report;
};

/// Skin landmarks on a head mesh found by registering the template's skin onto it (skull_registration.hpp: a
/// similarity from many starts, its scale free, then the non-rigid field) and moving each of the template's skin
/// points (its pairs' and its skin-only landmarks) to the closest point of the head: a start for landmarks that a
/// user checks and moves (3D Slicer). `rms_mm` receives the registration's trimmed RMS when not null. Throws
/// InputError for an empty head, or when the registration fails.
LandmarkSet skin_landmarks_by_registration(const TemplateHead& base, const TriMesh& head, double* rms_mm = nullptr);

/// The template made from `input` by carrying `base` onto it (steps above). Throws InputError naming the input:
/// no skin, fewer than 4 correspondences (no landmark of the subject pairs with one of the template's, or they
/// lie in one plane), landmark names the vocabulary does not know, a texture without skin UVs, options out of
/// range.
TemplateBuild build_template_head(const TemplateHead& base, const TemplateBuildInput& input,
                                  const TemplateBuildOptions& options = {});

}  // namespace forensim
