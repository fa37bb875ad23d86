#include "mesh_io/gltf_writer.hpp"

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "mesh_io/uv_seam_split.hpp"

namespace forensim {
namespace {

constexpr int gl_array_buffer = 34962;          // TINYGLTF_TARGET_ARRAY_BUFFER
constexpr int gl_element_array_buffer = 34963;  // TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER

bool is_png(const std::string& bytes) {
  return bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}
bool is_jpeg(const std::string& bytes) {
  return bytes.size() >= 3 && bytes.compare(0, 3, "\xFF\xD8\xFF") == 0;
}

/// Accumulates the single binary buffer and the views and accessors that point into it.
class ModelBuilder {
 public:
  explicit ModelBuilder(tinygltf::Model& model) : m_model(model) { m_model.buffers.emplace_back(); }

  /// Appends `bytes` at a 4-byte aligned offset (accessor alignment rule) and returns the view index.
  int add_view(const void* data, std::size_t bytes, int target) {
    std::vector<unsigned char>& buffer = m_model.buffers[0].data;
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    m_model.bufferViews.push_back(view);
    return static_cast<int>(m_model.bufferViews.size()) - 1;
  }

  /// Float accessor of `components` (1, 2, 3 or 4) per element, with min/max when `bounds` is set.
  int add_floats(const std::vector<float>& values, int components, int target, bool bounds) {
    tinygltf::Accessor a;
    a.bufferView = add_view(values.data(), values.size() * sizeof(float), target);
    a.byteOffset = 0;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = values.size() / static_cast<std::size_t>(components);
    a.type = components == 1   ? TINYGLTF_TYPE_SCALAR
             : components == 2 ? TINYGLTF_TYPE_VEC2
             : components == 3 ? TINYGLTF_TYPE_VEC3
                               : TINYGLTF_TYPE_VEC4;
    if (bounds && a.count > 0) {
      a.minValues.assign(components, std::numeric_limits<double>::infinity());
      a.maxValues.assign(components, -std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t c = i % static_cast<std::size_t>(components);
        a.minValues[c] = std::min<double>(a.minValues[c], values[i]);
        a.maxValues[c] = std::max<double>(a.maxValues[c], values[i]);
      }
    }
    m_model.accessors.push_back(a);
    return static_cast<int>(m_model.accessors.size()) - 1;
  }

  int add_indices(const std::vector<std::uint32_t>& indices) {
    tinygltf::Accessor a;
    a.bufferView = add_view(indices.data(), indices.size() * sizeof(std::uint32_t), gl_element_array_buffer);
    a.byteOffset = 0;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = indices.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    m_model.accessors.push_back(a);
    return static_cast<int>(m_model.accessors.size()) - 1;
  }

  /// Embeds an encoded image and returns its texture index.
  int add_texture(const std::string& bytes, const std::string& mime_type, const std::string& name) {
    if (m_model.samplers.empty()) {
      tinygltf::Sampler s;
      s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
      s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
      s.wrapS = TINYGLTF_TEXTURE_WRAP_REPEAT;
      s.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
      m_model.samplers.push_back(s);
    }
    tinygltf::Image image;
    image.name = name;
    image.mimeType = mime_type;
    image.bufferView = add_view(bytes.data(), bytes.size(), 0);
    m_model.images.push_back(image);
    tinygltf::Texture texture;
    texture.name = name;
    texture.sampler = 0;
    texture.source = static_cast<int>(m_model.images.size()) - 1;
    m_model.textures.push_back(texture);
    return static_cast<int>(m_model.textures.size()) - 1;
  }

 private:
  tinygltf::Model& m_model;
};

/// Encoded image for one material slot: given PNG bytes, else the file the material names, else none.
/// Returns {bytes, mime type}.
std::pair<std::string, std::string> texture_bytes(const std::string& given_png, const std::string& file,
                                                  const std::string& slot, const std::string& node,
                                                  const std::filesystem::path& folder) {
  if (!given_png.empty()) {
    require_input(is_png(given_png), "glTF node '" + node + "'", slot, "texture bytes are not a PNG image");
    return {given_png, "image/png"};
  }
  if (file.empty()) return {};
  std::filesystem::path p(file);
  if (p.is_relative()) p = folder / p;
  std::string bytes;
  try {
    bytes = read_file(p, std::size_t{1} << 30);
  } catch (const IoError& e) {
    spdlog::warn("glTF export: {} texture of '{}' not embedded: {}", slot, node, e.what());
    return {};
  }
  if (is_png(bytes)) return {bytes, "image/png"};
  if (is_jpeg(bytes)) return {bytes, "image/jpeg"};
  spdlog::warn("glTF export: {} texture '{}' of '{}' is neither PNG nor JPEG; not embedded", slot, p.string(), node);
  return {};
}

std::vector<float> scaled_vectors(const std::vector<Vec3>& values, const std::vector<Index>& source, double scale) {
  std::vector<float> out;
  out.reserve(source.size() * 3);
  for (Index v : source) {
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(values[static_cast<std::size_t>(v)][c] * scale));
  }
  return out;
}

void add_node(tinygltf::Model& model, ModelBuilder& builder, const GltfMeshNode& node, double scale,
              const std::filesystem::path& folder) {
  const std::string source = "glTF node '" + node.name + "'";
  const TriMesh& mesh = node.mesh;
  mesh.validate(source);
  require_input(!mesh.triangles.empty(), source, "", "mesh has no triangles");
  require_input(std::isfinite(scale) && scale > 0.0, "glTF write options", "metres_per_unit", "must be > 0");
  const std::size_t vertex_count = mesh.positions.size();
  for (std::size_t t = 0; t < node.morph_targets.size(); ++t) {
    const MorphTarget& target = node.morph_targets[t];
    const std::string location = "morph target " + std::to_string(t) + " '" + target.name + "'";
    require_input(target.position_deltas.size() == vertex_count, source, location,
                  std::to_string(target.position_deltas.size()) + " position deltas for " +
                      std::to_string(vertex_count) + " vertices");
    require_input(target.normal_deltas.empty() || target.normal_deltas.size() == vertex_count, source, location,
                  "normal delta count differs from the vertex count");
    for (const Vec3& d : target.position_deltas) require_input(d.allFinite(), source, location, "non-finite delta");
    for (const Vec3& d : target.normal_deltas) require_input(d.allFinite(), source, location, "non-finite delta");
  }
  require_input(node.default_weights.empty() || node.default_weights.size() == node.morph_targets.size(), source,
                "default weights", "count differs from the number of morph targets");
  require_input(node.translation.allFinite() && node.rotation.coeffs().allFinite() && node.rotation.norm() > 0.0,
                source, "transform", "translation or rotation is not finite");
  require_input(std::isfinite(node.scale) && node.scale >= 0.0, source, "transform",
                "scale is not a finite number >= 0");

  const SeamSplitMesh split = split_uv_seams(mesh);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] =
      builder.add_floats(scaled_vectors(mesh.positions, split.source_vertex, scale), 3, gl_array_buffer, true);
  if (mesh.has_normals()) {
    std::vector<Vec3> unit(mesh.normals.size());
    for (std::size_t v = 0; v < unit.size(); ++v) {
      const double length = mesh.normals[v].norm();
      unit[v] = length > 0.0 ? Vec3(mesh.normals[v] / length) : Vec3(0.0, 0.0, 1.0);
    }
    primitive.attributes["NORMAL"] =
        builder.add_floats(scaled_vectors(unit, split.source_vertex, 1.0), 3, gl_array_buffer, false);
  }
  if (mesh.has_uvs()) {
    std::vector<float> uv;
    uv.reserve(split.uvs.size() * 2);
    for (const Vec2& t : split.uvs) {
      uv.push_back(static_cast<float>(t[0]));
      uv.push_back(static_cast<float>(1.0 - t[1]));  // glTF's v axis points down
    }
    primitive.attributes["TEXCOORD_0"] = builder.add_floats(uv, 2, gl_array_buffer, false);
  }
  if (mesh.has_colors()) {
    std::vector<float> rgba;
    rgba.reserve(split.source_vertex.size() * 4);
    for (Index v : split.source_vertex) {
      for (int c = 0; c < 4; ++c) rgba.push_back(std::clamp(mesh.colors[static_cast<std::size_t>(v)][c], 0.0f, 1.0f));
    }
    primitive.attributes["COLOR_0"] = builder.add_floats(rgba, 4, gl_array_buffer, false);
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(split.triangles.size() * 3);
  for (const Tri& t : split.triangles) {
    for (Index i : t) indices.push_back(static_cast<std::uint32_t>(i));
  }
  primitive.indices = builder.add_indices(indices);

  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = node.name;
  if (!node.morph_targets.empty()) {
    tinygltf::Value::Array names;
    for (const MorphTarget& target : node.morph_targets) {
      std::map<std::string, int> attributes;
      // POSITION accessors of morph targets need min/max too (glTF 2.0, 3.7.2.2).
      attributes["POSITION"] =
          builder.add_floats(scaled_vectors(target.position_deltas, split.source_vertex, scale), 3, 0, true);
      if (!target.normal_deltas.empty()) {
        attributes["NORMAL"] =
            builder.add_floats(scaled_vectors(target.normal_deltas, split.source_vertex, 1.0), 3, 0, false);
      }
      primitive.targets.push_back(std::move(attributes));
      names.emplace_back(target.name);
    }
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(std::move(names));
    gltf_mesh.extras = tinygltf::Value(std::move(extras));
    gltf_mesh.weights =
        node.default_weights.empty() ? std::vector<double>(node.morph_targets.size(), 0.0) : node.default_weights;
  }

  // Material (PBR metallic-roughness).
  const Material& m = mesh.material;
  tinygltf::Material material;
  material.name = m.name.empty() ? node.name : m.name;
  material.pbrMetallicRoughness.baseColorFactor = {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]};
  material.pbrMetallicRoughness.metallicFactor = std::clamp(m.metallic, 0.0f, 1.0f);
  material.pbrMetallicRoughness.roughnessFactor = std::clamp(m.roughness, 0.0f, 1.0f);
  if (m.base_color[3] < 1.0f) material.alphaMode = "BLEND";
  const auto [base_bytes, base_mime] =
      texture_bytes(node.textures.base_color_png, m.base_color_texture, "base colour", node.name, folder);
  if (!base_bytes.empty())
    material.pbrMetallicRoughness.baseColorTexture.index =
        builder.add_texture(base_bytes, base_mime, node.name + " base colour");
  const auto [normal_bytes, normal_mime] =
      texture_bytes(node.textures.normal_png, m.normal_texture, "normal", node.name, folder);
  if (!normal_bytes.empty())
    material.normalTexture.index = builder.add_texture(normal_bytes, normal_mime, node.name + " normal");
  const auto [mr_bytes, mr_mime] =
      texture_bytes(node.textures.metallic_roughness_png, m.roughness_texture, "metallic-roughness", node.name, folder);
  if (!mr_bytes.empty())
    material.pbrMetallicRoughness.metallicRoughnessTexture.index =
        builder.add_texture(mr_bytes, mr_mime, node.name + " metallic-roughness");
  model.materials.push_back(material);
  primitive.material = static_cast<int>(model.materials.size()) - 1;

  gltf_mesh.primitives.push_back(std::move(primitive));
  model.meshes.push_back(std::move(gltf_mesh));

  tinygltf::Node gltf_node;
  gltf_node.name = node.name;
  gltf_node.mesh = static_cast<int>(model.meshes.size()) - 1;
  if (!node.translation.isZero(0.0)) {
    gltf_node.translation = {node.translation[0] * scale, node.translation[1] * scale, node.translation[2] * scale};
  }
  const Eigen::Quaterniond q = node.rotation.normalized();
  if (!q.isApprox(Eigen::Quaterniond::Identity(), 0.0)) gltf_node.rotation = {q.x(), q.y(), q.z(), q.w()};
  if (node.scale != 1.0) gltf_node.scale = {node.scale, node.scale, node.scale};
  model.nodes.push_back(std::move(gltf_node));
}

/// Keyframe times as 32-bit floats, checked finite, >= 0 and strictly increasing.
std::vector<float> keyframe_times(const std::vector<double>& times_s, const std::string& source) {
  require_input(!times_s.empty(), source, "times", "no keyframes");
  std::vector<float> times;
  for (std::size_t k = 0; k < times_s.size(); ++k) {
    const std::string location = "keyframe " + std::to_string(k);
    const double t = times_s[k];
    require_input(std::isfinite(t) && t >= 0.0, source, location, "time is not a finite number >= 0");
    require_input(k == 0 || static_cast<float>(t) > times.back(), source, location,
                  "times must increase strictly (as 32-bit floats)");
    times.push_back(static_cast<float>(t));
  }
  return times;
}

/// Adds a sampler and its channel to the glTF animation called `name` (created when new).
void add_channel(tinygltf::Model& model, ModelBuilder& builder, const std::string& name,
                 const std::vector<float>& times, const std::vector<float>& values, GltfInterpolation interpolation,
                 std::size_t node, const std::string& path) {
  auto it = std::find_if(model.animations.begin(), model.animations.end(),
                         [&](const tinygltf::Animation& a) { return a.name == name; });
  if (it == model.animations.end()) {
    tinygltf::Animation created;
    created.name = name;
    model.animations.push_back(std::move(created));
    it = model.animations.end() - 1;
  }
  tinygltf::AnimationSampler sampler;
  sampler.input = builder.add_floats(times, 1, 0, true);  // input accessors need min/max
  sampler.output = builder.add_floats(values, path == "scale" ? 3 : 1, 0, false);
  sampler.interpolation = interpolation == GltfInterpolation::step ? "STEP" : "LINEAR";
  tinygltf::AnimationChannel channel;
  channel.sampler = static_cast<int>(it->samplers.size());
  channel.target_node = static_cast<int>(node);
  channel.target_path = path;
  it->samplers.push_back(sampler);
  it->channels.push_back(channel);
}

void add_scale_animation(tinygltf::Model& model, ModelBuilder& builder, const GltfScene& scene,
                         const NodeScaleAnimation& animation) {
  const std::string source = "glTF animation '" + animation.name + "'";
  require_input(animation.node < scene.nodes.size(), source, "node",
                "node " + std::to_string(animation.node) + " does not exist");
  const std::vector<float> times = keyframe_times(animation.times_s, source);
  require_input(animation.scales.size() == times.size(), source, "scales",
                std::to_string(animation.scales.size()) + " scales for " + std::to_string(times.size()) + " keyframes");
  std::vector<float> values;
  for (double s : animation.scales) {
    require_input(std::isfinite(s) && s >= 0.0, source, "scales", "scale is not a finite number >= 0");
    values.insert(values.end(), 3, static_cast<float>(s));
  }
  add_channel(model, builder, animation.name, times, values, animation.interpolation, animation.node, "scale");
}

void add_animation(tinygltf::Model& model, ModelBuilder& builder, const GltfScene& scene,
                   const MorphWeightAnimation& animation) {
  const std::string source = "glTF animation '" + animation.name + "'";
  require_input(animation.node < scene.nodes.size(), source, "node",
                "node " + std::to_string(animation.node) + " does not exist");
  const std::size_t targets = scene.nodes[animation.node].morph_targets.size();
  require_input(targets > 0, source, "node", "the animated node has no morph targets");
  const std::vector<float> times = keyframe_times(animation.times_s, source);
  require_input(animation.weights.size() == animation.times_s.size(), source, "weights",
                std::to_string(animation.weights.size()) + " weight rows for " +
                    std::to_string(animation.times_s.size()) + " keyframes");
  std::vector<float> weights;
  for (std::size_t k = 0; k < animation.times_s.size(); ++k) {
    const std::string location = "keyframe " + std::to_string(k);
    require_input(
        animation.weights[k].size() == targets, source, location,
        std::to_string(animation.weights[k].size()) + " weights for " + std::to_string(targets) + " morph targets");
    for (double w : animation.weights[k]) {
      require_input(std::isfinite(w), source, location, "weight is not finite");
      weights.push_back(static_cast<float>(w));
    }
  }
  add_channel(model, builder, animation.name, times, weights, animation.interpolation, animation.node, "weights");
}

}  // namespace

void write_gltf(const std::filesystem::path& path, const GltfScene& scene, const GltfWriteOptions& options) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  require_input(ext == ".glb" || ext == ".gltf", path.string(), "", "glTF output needs a .glb or .gltf name");
  require_input(!scene.nodes.empty(), path.string(), "", "the scene has no meshes");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "forensim";
  ModelBuilder builder(model);
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  tinygltf::Scene gltf_scene;
  for (const GltfMeshNode& node : scene.nodes) {
    add_node(model, builder, node, options.metres_per_unit, folder);
    gltf_scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  for (const MorphWeightAnimation& animation : scene.animations) add_animation(model, builder, scene, animation);
  for (const NodeScaleAnimation& animation : scene.scale_animations)
    add_scale_animation(model, builder, scene, animation);
  model.scenes.push_back(gltf_scene);
  model.defaultScene = 0;
  model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4, 0);

  AtomicFile file(path, true);
  tinygltf::TinyGLTF writer;
  const bool binary = ext == ".glb";
  if (!writer.WriteGltfSceneToStream(&model, file.stream(), !binary, binary)) {
    throw IoError(path.string(), "tinygltf could not serialise the scene");
  }
  file.commit();
}

void write_gltf(const std::filesystem::path& path, const TriMesh& mesh, const GltfWriteOptions& options) {
  GltfScene scene;
  GltfMeshNode node;
  node.name = path.stem().string();
  node.mesh = mesh;
  scene.nodes.push_back(std::move(node));
  write_gltf(path, scene, options);
}

}  // namespace forensim
