// glTF export checked value by value with tinygltf's own loader: morph targets following the seam split,
// target names, the weight animation, accessor bounds, alignment and buffer-view targets.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>

#include "core/error.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io_test_meshes.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

tinygltf::Model load(const std::filesystem::path& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const bool binary = path.extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path.string())
                         : loader.LoadASCIIFromFile(&model, &error, &warning, path.string());
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  return model;
}

/// Reads a tightly packed float accessor.
std::vector<float> floats(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(accessor_index));
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  std::vector<float> out(a.count * static_cast<std::size_t>(components));
  const unsigned char* data = model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data();
  std::memcpy(out.data(), data + view.byteOffset + a.byteOffset, out.size() * sizeof(float));
  return out;
}

struct MorphScene {
  GltfScene scene;
  TriMesh box;
};

/// Box with two morph targets ("swell": every vertex moves along x by its index; "shrink": scaled toward
/// the centre, with normal deltas) and a three-keyframe animation.
MorphScene morph_scene(GltfInterpolation interpolation) {
  MorphScene s;
  s.box = test::make_uv_box(Vec3(-50, -60, -70), Vec3(50, 60, 70), 1);
  GltfMeshNode node;
  node.name = "drying skin";
  node.mesh = s.box;
  MorphTarget swell{"swell", {}, {}}, shrink{"shrink", {}, {}};
  for (std::size_t v = 0; v < s.box.vertex_count(); ++v) {
    swell.position_deltas.emplace_back(static_cast<double>(v), 0.0, 0.0);
    shrink.position_deltas.push_back(-0.25 * s.box.positions[v]);
    shrink.normal_deltas.emplace_back(0.0, 0.0, 0.01 * static_cast<double>(v));
  }
  node.morph_targets = {swell, shrink};
  node.default_weights = {0.0, 0.5};
  node.textures.base_color_png = test::tiny_png();
  node.textures.normal_png = test::tiny_png();
  node.textures.metallic_roughness_png = test::tiny_png();
  s.scene.nodes.push_back(node);
  MorphWeightAnimation animation;
  animation.name = "desiccation";
  animation.node = 0;
  animation.times_s = {0.0, 1.5, 4.0};
  animation.weights = {{0.0, 0.0}, {0.25, 0.5}, {1.0, 1.0}};
  animation.interpolation = interpolation;
  s.scene.animations.push_back(animation);
  return s;
}

}  // namespace

TEST(GltfWriter, MorphTargetsFollowTheSeamSplitValueByValue) {
  const auto dir = test::scratch_dir("morph");
  const MorphScene s = morph_scene(GltfInterpolation::linear);
  write_gltf(dir / "skin.glb", s.scene);
  const tinygltf::Model model = load(dir / "skin.glb");

  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Mesh& mesh = model.meshes[0];
  EXPECT_EQ(mesh.name, "drying skin");
  ASSERT_EQ(mesh.weights.size(), 2u);
  EXPECT_DOUBLE_EQ(mesh.weights[1], 0.5);
  const tinygltf::Value& names = mesh.extras.Get("targetNames");
  ASSERT_TRUE(names.IsArray());
  ASSERT_EQ(names.ArrayLen(), 2u);
  EXPECT_EQ(names.Get(0).Get<std::string>(), "swell");
  EXPECT_EQ(names.Get(1).Get<std::string>(), "shrink");

  const tinygltf::Primitive& primitive = mesh.primitives.at(0);
  const std::vector<float> positions = floats(model, primitive.attributes.at("POSITION"));
  const std::size_t count = positions.size() / 3;
  EXPECT_EQ(count, 24u);  // 8 box corners, each split into 3 by the face seams
  ASSERT_EQ(primitive.targets.size(), 2u);
  const std::vector<float> swell = floats(model, primitive.targets[0].at("POSITION"));
  const std::vector<float> shrink = floats(model, primitive.targets[1].at("POSITION"));
  const std::vector<float> shrink_normals = floats(model, primitive.targets[1].at("NORMAL"));
  EXPECT_EQ(primitive.targets[0].count("NORMAL"), 0u);
  ASSERT_EQ(swell.size(), positions.size());
  for (std::size_t i = 0; i < count; ++i) {
    // Find the welded vertex this split vertex copies (positions in metres).
    const Vec3 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    std::size_t v = s.box.vertex_count();
    for (std::size_t k = 0; k < s.box.vertex_count(); ++k) {
      if ((s.box.positions[k] * 0.001 - p).norm() < 1e-6) v = k;
    }
    ASSERT_LT(v, s.box.vertex_count()) << "split vertex " << i;
    EXPECT_NEAR(swell[3 * i], 0.001 * static_cast<double>(v), 1e-7);
    EXPECT_EQ(swell[3 * i + 1], 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(shrink[3 * i + c], -0.25 * 0.001 * s.box.positions[v][c], 1e-7);
    EXPECT_NEAR(shrink_normals[3 * i + 2], 0.01 * static_cast<double>(v), 1e-6);
  }

  // Accessor bounds (POSITION, and morph POSITION, must have exact min/max).
  for (int accessor : {primitive.attributes.at("POSITION"), primitive.targets[0].at("POSITION"),
                       primitive.targets[1].at("POSITION")}) {
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(accessor)];
    const std::vector<float> values = floats(model, accessor);
    ASSERT_EQ(a.minValues.size(), 3u);
    ASSERT_EQ(a.maxValues.size(), 3u);
    for (int c = 0; c < 3; ++c) {
      float lo = values[static_cast<std::size_t>(c)], hi = lo;
      for (std::size_t i = static_cast<std::size_t>(c); i < values.size(); i += 3) {
        lo = std::min(lo, values[i]);
        hi = std::max(hi, values[i]);
      }
      EXPECT_EQ(a.minValues[static_cast<std::size_t>(c)], static_cast<double>(lo));
      EXPECT_EQ(a.maxValues[static_cast<std::size_t>(c)], static_cast<double>(hi));
    }
  }

  // Alignment and buffer-view targets.
  for (const tinygltf::BufferView& view : model.bufferViews) EXPECT_EQ(view.byteOffset % 4, 0u);
  EXPECT_EQ(model
                .bufferViews[static_cast<std::size_t>(
                    model.accessors[static_cast<std::size_t>(primitive.indices)].bufferView)]
                .target,
            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  EXPECT_EQ(model
                .bufferViews[static_cast<std::size_t>(
                    model.accessors[static_cast<std::size_t>(primitive.attributes.at("NORMAL"))].bufferView)]
                .target,
            TINYGLTF_TARGET_ARRAY_BUFFER);
  const tinygltf::Accessor& indices = model.accessors[static_cast<std::size_t>(primitive.indices)];
  EXPECT_EQ(indices.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(indices.count, 3u * s.box.triangle_count());

  // Material with three embedded PNGs.
  const tinygltf::Material& material = model.materials.at(static_cast<std::size_t>(primitive.material));
  EXPECT_GE(material.pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_GE(material.normalTexture.index, 0);
  EXPECT_GE(material.pbrMetallicRoughness.metallicRoughnessTexture.index, 0);
  EXPECT_NEAR(material.pbrMetallicRoughness.roughnessFactor, 0.7, 1e-6);
  ASSERT_EQ(model.images.size(), 3u);
  for (const tinygltf::Image& image : model.images) {
    EXPECT_EQ(image.mimeType, "image/png");
    EXPECT_EQ(image.width, 2);
    EXPECT_EQ(image.height, 2);
  }
}

TEST(GltfWriter, AnimationKeyframesAndInterpolationReadBack) {
  const auto dir = test::scratch_dir("animation");
  for (const GltfInterpolation interpolation : {GltfInterpolation::linear, GltfInterpolation::step}) {
    const MorphScene s = morph_scene(interpolation);
    write_gltf(dir / "skin.gltf", s.scene);
    const tinygltf::Model model = load(dir / "skin.gltf");
    ASSERT_EQ(model.animations.size(), 1u);
    const tinygltf::Animation& animation = model.animations[0];
    EXPECT_EQ(animation.name, "desiccation");
    ASSERT_EQ(animation.channels.size(), 1u);
    EXPECT_EQ(animation.channels[0].target_node, 0);
    EXPECT_EQ(animation.channels[0].target_path, "weights");
    const tinygltf::AnimationSampler& sampler = animation.samplers.at(0);
    EXPECT_EQ(sampler.interpolation, interpolation == GltfInterpolation::step ? "STEP" : "LINEAR");
    const std::vector<float> times = floats(model, sampler.input);
    const std::vector<float> weights = floats(model, sampler.output);
    ASSERT_EQ(times.size(), 3u);
    EXPECT_EQ(times[1], 1.5f);
    EXPECT_EQ(model.accessors[static_cast<std::size_t>(sampler.input)].minValues.at(0), 0.0);
    EXPECT_EQ(model.accessors[static_cast<std::size_t>(sampler.input)].maxValues.at(0), 4.0);
    const std::vector<float> expected = {0.0f, 0.0f, 0.25f, 0.5f, 1.0f, 1.0f};
    EXPECT_EQ(weights, expected);
  }
}

TEST(GltfWriter, InconsistentMorphDataIsRejected) {
  const auto dir = test::scratch_dir("bad-morph");
  MorphScene s = morph_scene(GltfInterpolation::linear);
  s.scene.nodes[0].morph_targets[0].position_deltas.pop_back();
  EXPECT_THROW(write_gltf(dir / "a.glb", s.scene), InputError);
  s = morph_scene(GltfInterpolation::linear);
  s.scene.animations[0].times_s = {0.0, 2.0, 1.0};
  EXPECT_THROW(write_gltf(dir / "b.glb", s.scene), InputError);
  s = morph_scene(GltfInterpolation::linear);
  s.scene.animations[0].weights[2] = {1.0};
  EXPECT_THROW(write_gltf(dir / "c.glb", s.scene), InputError);
  s = morph_scene(GltfInterpolation::linear);
  s.scene.nodes[0].textures.normal_png = "not a png";
  EXPECT_THROW(write_gltf(dir / "d.glb", s.scene), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// A per-frame sequence: a second node hidden at first (scale 0) and shown by a STEP scale animation that shares
// the weight animation's name, so both land in one glTF animation (one clip) with their own samplers.
TEST(GltfWriter, ScaleAnimationsJoinTheClipOfTheSameName) {
  const auto dir = test::scratch_dir("scale-animation");
  MorphScene s = morph_scene(GltfInterpolation::linear);
  GltfMeshNode second;
  second.name = "frame 1";
  second.mesh = s.box;
  second.scale = 0.0;
  s.scene.nodes.push_back(second);
  s.scene.scale_animations.push_back({"desiccation", 0, {0.0, 4.0}, {1.0, 0.0}, GltfInterpolation::step});
  s.scene.scale_animations.push_back({"desiccation", 1, {0.0, 4.0}, {0.0, 1.0}, GltfInterpolation::step});
  s.scene.scale_animations.push_back({"other", 1, {0.0}, {2.0}, GltfInterpolation::linear});
  write_gltf(dir / "frames.glb", s.scene);
  const tinygltf::Model model = load(dir / "frames.glb");
  ASSERT_EQ(model.nodes.size(), 2u);
  EXPECT_TRUE(model.nodes[0].scale.empty());  // scale 1 is glTF's default
  EXPECT_EQ(model.nodes[1].scale, (std::vector<double>{0.0, 0.0, 0.0}));
  ASSERT_EQ(model.animations.size(), 2u);
  const tinygltf::Animation& clip = model.animations[0];
  EXPECT_EQ(clip.name, "desiccation");
  ASSERT_EQ(clip.channels.size(), 3u);
  ASSERT_EQ(clip.samplers.size(), 3u);
  EXPECT_EQ(clip.channels[0].target_path, "weights");
  for (int c = 1; c < 3; ++c) {
    const tinygltf::AnimationChannel& channel = clip.channels[static_cast<std::size_t>(c)];
    EXPECT_EQ(channel.target_path, "scale");
    EXPECT_EQ(channel.target_node, c - 1);
    EXPECT_EQ(channel.sampler, c);
    const tinygltf::AnimationSampler& sampler = clip.samplers[static_cast<std::size_t>(c)];
    EXPECT_EQ(sampler.interpolation, "STEP");
    EXPECT_EQ(floats(model, sampler.input), (std::vector<float>{0.0f, 4.0f}));
    const float a = c == 1 ? 1.0f : 0.0f, b = 1.0f - a;
    EXPECT_EQ(floats(model, sampler.output), (std::vector<float>{a, a, a, b, b, b}));
  }
  EXPECT_EQ(model.animations[1].name, "other");
  EXPECT_EQ(model.animations[1].channels.size(), 1u);

  s.scene.scale_animations[0].scales = {1.0, -1.0};
  EXPECT_THROW(write_gltf(dir / "bad.glb", s.scene), InputError);
  s.scene.scale_animations[0].scales = {1.0};
  EXPECT_THROW(write_gltf(dir / "bad.glb", s.scene), InputError);
  s.scene.scale_animations[0].scales = {1.0, 0.0};
  s.scene.nodes[1].scale = -1.0;
  EXPECT_THROW(write_gltf(dir / "bad.glb", s.scene), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
}
