#pragma once
/// glTF 2.0 export (binary .glb or JSON .gltf) through tinygltf: the format Blender, Unreal, three.js and
/// the forensim web viewer load directly. Besides static meshes with PBR materials and embedded textures it
/// carries morph targets and weight animations, which is how the desiccation system exports drying skin
/// over time and how craniofacial expressions are exported.

#include <filesystem>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// One blend shape of a mesh: displacements of its welded vertices.
struct MorphTarget {
  std::string name;                   ///< written to mesh.extras.targetNames (Blender's shape-key names)
  std::vector<Vec3> position_deltas;  ///< #V displacement of each welded vertex, mm
  std::vector<Vec3> normal_deltas;    ///< #V change of each unit normal, or empty
};

/// Already-encoded PNG images embedded into the file. Empty strings mean "no texture".
struct GltfTextures {
  std::string base_color_png;          ///< sRGB base colour (multiplied by Material::base_color)
  std::string normal_png;              ///< tangent-space normal map
  std::string metallic_roughness_png;  ///< glTF packing: roughness in G, metallic in B
};

/// A named mesh placed in the scene by its own node.
struct GltfMeshNode {
  std::string name;
  TriMesh mesh;  ///< welded, millimetres; UVs, normals and colours are written when present
  std::vector<MorphTarget> morph_targets;
  std::vector<double> default_weights;  ///< #targets initial weights, or empty (all zero)
  /// Encoded textures. Where one is empty and mesh.material names a texture file (PNG or JPEG; relative
  /// paths against the output's folder), that file is embedded instead.
  GltfTextures textures;
  Vec3 translation = Vec3::Zero();                               ///< node translation, mm
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< node rotation
  double scale = 1.0;  ///< uniform node scale (>= 0; 0 hides the node until an animation shows it)
};

enum class GltfInterpolation { linear, step };

/// Keyframed morph weights of one node (glTF animation channel with path "weights").
struct MorphWeightAnimation {
  std::string name;
  std::size_t node = 0;                      ///< index into GltfScene::nodes
  std::vector<double> times_s;               ///< #K strictly increasing keyframe times, seconds
  std::vector<std::vector<double>> weights;  ///< #K rows of #targets weights
  GltfInterpolation interpolation = GltfInterpolation::linear;
};

/// Keyframed uniform scale of one node (glTF animation channel with path "scale"). With STEP interpolation
/// between 0 and 1 it shows a node for a span of time: how a sequence of per-frame meshes (one node per frame,
/// each with its own colours or textures) plays in Blender and three.js.
struct NodeScaleAnimation {
  std::string name;
  std::size_t node = 0;         ///< index into GltfScene::nodes
  std::vector<double> times_s;  ///< #K strictly increasing keyframe times, seconds
  std::vector<double> scales;   ///< #K uniform scales (>= 0)
  GltfInterpolation interpolation = GltfInterpolation::step;
};

/// Animations that share a name are written as the channels of one glTF animation (one clip that players
/// run as a whole), in the order given: weight animations first, then scale animations.
struct GltfScene {
  std::vector<GltfMeshNode> nodes;
  std::vector<MorphWeightAnimation> animations;
  std::vector<NodeScaleAnimation> scale_animations;
};

struct GltfWriteOptions {
  /// Metres per forensim length unit: glTF is in metres and forensim in millimetres, so 0.001. Positions,
  /// position deltas and translations are multiplied by it.
  double metres_per_unit = 0.001;
};

/// Writes `scene` as glTF 2.0: binary GLB for a .glb path, JSON with the buffer embedded as base64 for
/// .gltf. Each node's mesh becomes one triangle primitive with POSITION (with the min/max the spec
/// requires), NORMAL, TEXCOORD_0 (glTF's v points down: v' = 1 - v), COLOR_0 and uint32 indices; vertices
/// are split at UV seams and morph targets follow the split. Material: PBR metallic-roughness from
/// mesh.material with embedded textures. Written atomically. Throws InputError for inconsistent input
/// (delta counts, weight rows, non-increasing times, non-PNG texture bytes), IoError on write failure.
void write_gltf(const std::filesystem::path& path, const GltfScene& scene, const GltfWriteOptions& options = {});

/// Writes one mesh as a one-node glTF scene named after the file's stem.
void write_gltf(const std::filesystem::path& path, const TriMesh& mesh, const GltfWriteOptions& options = {});

}  // namespace forensim
