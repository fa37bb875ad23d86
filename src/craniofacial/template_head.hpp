#pragma once
/// The built-in template head of the craniofacial reconstruction (Kähler, Haber and Seidel 2003, section 4.1,
/// Figure 5): the `head` phantom's skin as a triangle mesh with a UV atlas (so procedural skin maps and the
/// reconstructed head's texture survive the warp, Figure 1d), its skull, landmark pairs (a skull landmark, its
/// outward skull normal and the skin landmark where that normal meets the skin) and the 24 facial muscles as
/// layout grids on the skin.
///
/// Skull landmarks are found on the phantom's bone by their definitions (reference/tissue-depth.md, Caple and
/// Stephan 2016): midline points on the midsagittal profile x = 0 (glabella the most anterior point between the
/// brows, nasion the deepest point between glabella and the nasal bones, rhinion the end of the nasal bones,
/// mid-nasal their midpoint, subspinale the deepest point below the nasal aperture, prosthion and infradentale
/// where the alveolar bone meets the incisors, supramentale the deepest point between infradentale and
/// pogonion, pogonion the most anterior point of the chin, menton the lowest point of the symphysis, gnathion
/// midway between them), extremal points (vertex highest, opisthocranion most posterior, zygion most lateral on
/// the arch, gonion at the mandibular angle) and bilateral points from the dental arch (supra/infra-canine over
/// the canine roots, ecm2 at the second molar) and the orbits (mid-supraorbital/infraorbital on the vertical
/// through the orbit's centre), alar curvature 5 mm lateral to the nasal aperture's widest point. Names are the
/// T-Table abbreviations; bilateral ones end in _L or _R (the patient's side: x > 0 is left in LPS). Skin
/// landmarks carry the table's primed names ("se'" for nasion, "sM2'_L" and "iM2'_L" for the upper and lower
/// ecm2). Skin-only landmarks: pronasale the most anterior point of the nose, alare the most lateral point of
/// each nose wing, stomion the midline point of the lips' parting, cheilion the lateral end of the phantom's
/// mouth slit. Frame: the phantom's LPS millimetres (x left, y posterior, z superior; the face looks toward -y).

#include <functional>
#include <string>
#include <vector>

#include "craniofacial/muscle_layout.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct TemplateHeadOptions {
  double skin_voxel_mm = 2.0;  ///< grid spacing of the skin iso-surface
  double skin_edge_mm = 4.0;   ///< target edge of the isotropic remeshing (the paper's template: 8164 triangles)
  int remesh_iterations = 3;
  double skull_voxel_mm = 1.5;  ///< grid spacing of the skull iso-surface
  bool uv_atlas = true;         ///< build the UV atlas (charts below) on the skin
  int uv_resolution = 1024;     ///< texture size the atlas gutter is measured in
  int muscle_fibres = 5;
  int muscle_samples = 9;
};

/// One skull-to-skin landmark pair of the template.
struct TemplateLandmarkPair {
  std::string bone_name;             ///< skull landmark: "g", "n", "zy_L", "ecm2_R", ...
  std::string skin_name;             ///< its skin counterpart: "g'", "se'", "zy'_L", "sM2'_R" / "iM2'_R", ...
  Vec3 skull = Vec3::Zero();         ///< on the skull mesh, mm
  Vec3 skull_normal = Vec3::Zero();  ///< unit outward normal of the skull there (the depth direction)
  Vec3 skin = Vec3::Zero();          ///< where skull + t * skull_normal (t > 0) first meets the skin mesh
  double depth_mm = 0.0;             ///< t: the template's own soft-tissue thickness there
  bool midline = false;
};

/// A landmark defined on the skin only (no skull counterpart): the nose and mouth points that the paper's
/// guides move in the second warp (section 4.3).
struct TemplateSkinLandmark {
  std::string name;  ///< "prn'" (pronasale), "al'_L"/"al'_R" (alare), "ch'_L"/"ch'_R" (cheilion), "sto'" (stomion)
  Vec3 position = Vec3::Zero();  ///< on the skin mesh, mm
};

struct TemplateHead {
  TriMesh skin;                          ///< mm, vertex normals, corner UVs when options.uv_atlas
  std::vector<int> triangle_chart;       ///< #F chart of each skin triangle (index into chart_names)
  std::vector<std::string> chart_names;  ///< "top", "bottom", "face", "left", "right", "back"
  double uv_l2_stretch = 0.0;            ///< the atlas's normalised L2 stretch (Sander et al. 2001)
  bool uv_overlap_free = false;
  TriMesh skull;  ///< cranium, mandible and teeth (the cervical spine is left out), mm
  std::vector<TemplateLandmarkPair> landmarks;
  std::vector<TemplateSkinLandmark> skin_landmarks;
  std::vector<MuscleLayout> muscles;  ///< the 24 muscles, grids on the skin
  /// What the template was made from ("built-in template head", or the head mesh / CT of forensim template build).
  std::string source = "built-in template head (head phantom)";
  /// The skin's own base-colour map (PNG bytes, on the skin's UVs), or empty: procedural skin maps are made on the
  /// atlas. A template built from a textured head mesh carries that texture baked onto its atlas.
  std::string texture_png;
  /// Seconds to build, and its stages: the skin surface, then its atlas and muscles (make_template_skin), beside the
  /// skull with its landmarks (make_template_skull), then the skin points of the landmarks (join_template_head).
  double seconds = 0.0;
  double seconds_skin = 0.0, seconds_skull = 0.0, seconds_landmarks = 0.0, seconds_atlas = 0.0;
};

/// The skin half of the template head (make_template_skin): independent of the skull.
struct TemplateSkin {
  TriMesh surface;                       ///< the remeshed skin before the atlas's cuts (landmarks are found on it)
  TriMesh skin;                          ///< as TemplateHead::skin (with UVs when options.uv_atlas)
  std::vector<int> triangle_chart;       ///< as TemplateHead
  std::vector<std::string> chart_names;  ///< as TemplateHead
  double uv_l2_stretch = 0.0;
  bool uv_overlap_free = false;
  std::vector<MuscleLayout> muscles;  ///< on `skin`
  double seconds_surface = 0.0, seconds_atlas = 0.0;
};

/// The template options of a detail level, as `forensim reconstruct --template-detail` and the skull editor
/// name them: "full" (the defaults) or "coarse" (3 mm voxels, 6 mm edges: quicker). Throws InputError for
/// other names.
TemplateHeadOptions template_head_options(const std::string& detail);

/// Builds the template head (deterministic). Throws InputError for options out of range (skin_voxel_mm and
/// skull_voxel_mm in [0.5, 5], skin_edge_mm in [skin_voxel_mm / 2, 15]) and NumericError if a landmark
/// cannot be found on the phantom.
TemplateHead make_template_head(const TemplateHeadOptions& options = {});

/// make_template_head in three steps, so that work needing only the skull (automatic landmark detection) may run
/// while the skin is built: make_template_skull gives a head with the skull and the landmark pairs' skull side
/// (bone_name, skin_name, skull, skull_normal, midline; skin, depth_mm, the skin and its landmarks still empty);
/// make_template_skin the skin, its atlas and the muscles; join_template_head the pairs' skin points and the
/// skin landmarks. join_template_head(make_template_skull(o), make_template_skin(o)) equals make_template_head(o).
/// Throw as make_template_head; join_template_head throws InputError for an empty part.
TemplateHead make_template_skull(const TemplateHeadOptions& options = {});
/// make_template_head with `with_skull` called on the skull part (make_template_skull) while the skin is built
/// beside it, before the two are joined: work that needs only the template's skull (reading a CT, automatic
/// landmark detection) overlaps the skin's remeshing, atlas and muscles.
TemplateHead make_template_head_beside(const TemplateHeadOptions& options,
                                       const std::function<void(const TemplateHead& skull_part)>& with_skull);
TemplateSkin make_template_skin(const TemplateHeadOptions& options = {});
TemplateHead join_template_head(TemplateHead skull_part, TemplateSkin skin);

/// Index of the pair whose skin_name or (unique) bone_name is `name`, or -1. Throws InputError when a bone
/// name matches several pairs (ecm2_L pairs with sM2'_L and iM2'_L): use the skin name then.
int find_template_landmark(const TemplateHead& head, const std::string& name);

/// The skull landmark positions the definitions give on the phantom's bone signed distance function, before
/// they are moved onto the skull mesh: bone names as in TemplateLandmarkPair, positions in mm. For tests and
/// for locating the same points on other skulls.
struct PhantomSkullLandmark {
  std::string bone_name;
  std::string skin_name;
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  ///< unit outward normal (gradient of the bone distance)
  bool midline = false;
};
std::vector<PhantomSkullLandmark> head_phantom_skull_landmarks();

}  // namespace forensim
