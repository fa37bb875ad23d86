#pragma once
/// Scene recipes the CLI uses for its pictures: a surface alone, skin semi-transparent over bone, a
/// cut-away through skin and bone, and material choices by name.

#include <memory>
#include <string>
#include <vector>

#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"
#include "render/render_settings.hpp"
#include "render/scene.hpp"
#include "render/sheet.hpp"

namespace forensim::cli {

/// A material by name: "skin", "bone", "clay", "vertex" (vertex colours), "texture" (the mesh's base colour
/// texture through its UVs, which must be loaded into `texture`), or "field:NAME" (a per-vertex scalar
/// field through viridis over its range). Throws a usage Error for other names.
SurfaceMaterial material_from_name(const std::string& name, const TriMesh& mesh,
                                   std::shared_ptr<const Image> texture = nullptr);

/// The material a mesh suggests: its texture when it has one loaded, vertex colours when it has them, clay else.
SurfaceMaterial default_material(const TriMesh& mesh, std::shared_ptr<const Image> texture = nullptr);

/// Loads a mesh's base colour texture (PNG/JPEG/EXR file referenced by its material), or null when it has
/// none or it cannot be read (a warning is logged).
std::shared_ptr<const Image> load_base_texture(const TriMesh& mesh);

/// Scene of skin (semi-transparent at `skin_opacity`) over bone, framed from `view`.
Scene skin_over_bone_scene(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const TriMesh> bone,
                           double skin_opacity, const ViewAxes& axes);

/// Draws tissue-depth vectors into `scene`: a line from each skull point to its skin point and a dot on the skull
/// (the paper's Figures 1 and 9).
void add_depth_vectors(Scene& scene, const std::vector<std::pair<Vec3, Vec3>>& skull_to_skin);

/// Scene of skin and bone cut by the plane through the skin's centre with normal `cut_normal` (the side the
/// normal points to is removed), showing bone inside flesh.
Scene cutaway_scene(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const TriMesh> bone, const Vec3& cut_normal,
                    const ViewAxes& axes);

/// Renders `scene` from the named view (framed around the scene).
Image render_view(Scene scene, const RenderSettings& settings, const std::string& view, const ViewAxes& axes);

/// The pictures of a built-in phantom: skin from two sides, skin over bone, and a cut-away showing bone
/// inside flesh (the arm from above and from the thumb side; the head from the front and the left).
std::vector<SheetCell> phantom_view_cells(const std::string& phantom_name, std::shared_ptr<const TriMesh> skin,
                                          std::shared_ptr<const TriMesh> bone, const RenderSettings& settings);

/// Scene of the tets on one side of the plane through the mesh's centre with normal `cut_normal` (the side
/// the normal points to is removed), flesh and bone with the tet faces drawn as a wireframe, so the cut shows
/// the elements and the bone inside the flesh.
Scene tet_cutaway_scene(const TetMesh& mesh, const Vec3& cut_normal, const ViewAxes& axes);

/// How to look at a body part: its axes, two named views of the skin with captions, and the cut normal and
/// view of a cut-away (the arm from the back of the hand, cut dorsally; heads from the left, cut through
/// the midsagittal plane).
struct BodyViews {
  ViewAxes axes;
  std::string view_a, caption_a, view_b, caption_b;
  Vec3 cut_normal;
  std::string cut_view;
};
/// Views for "arm" (x distal, z dorsal) and for heads in the given axes (any other name).
BodyViews body_views(const std::string& kind, const ViewAxes& axes = {});

/// Pictures of a tet model: the skin from two sides and the tet cut-away.
std::vector<SheetCell> tet_model_cells(const BodyViews& views, std::shared_ptr<const TriMesh> skin,
                                       const TetMesh& volume, const RenderSettings& settings);

/// Pictures of a skin with its maps (linear epidermis colour and tangent-space normal map through the mesh's
/// UVs): the back of the hand and the palm of the arm frame, and the colour map itself (the UV layout).
std::vector<SheetCell> textured_arm_cells(std::shared_ptr<const TriMesh> skin, std::shared_ptr<const Image> colour,
                                          std::shared_ptr<const Image> normal, const RenderSettings& settings);

/// Axes by name: "lps" (CT: z up, -y front) or "yup" (glTF/OBJ heads: y up, +z front).
ViewAxes axes_from_name(const std::string& name);

}  // namespace forensim::cli
