#include "mesh_io/mesh_import.hpp"

#include <spdlog/spdlog.h>

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <exception>
#include <unordered_map>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "mesh_io/mesh_file_check.hpp"

namespace forensim {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// Exact-position key; -0.0 is folded onto 0.0 so both weld.
struct PositionKey {
  std::uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (std::uint64_t b : k.bits) {
      h ^= b + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      h *= 0xBF58476D1CE4E5B9ull;
    }
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

PositionKey key_of(const Vec3& p) {
  PositionKey k{};
  for (int i = 0; i < 3; ++i) {
    const double v = p[i] == 0.0 ? 0.0 : p[i];
    std::memcpy(&k.bits[i], &v, sizeof v);
  }
  return k;
}

Mat4 to_mat4(const aiMatrix4x4& m) {
  Mat4 r;
  r << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return r;
}

/// Millimetres per unit that "auto" means for this file.
double auto_mm_per_unit(const std::string& ext, const aiScene& scene) {
  if (ext == ".gltf" || ext == ".glb") return 1000.0;
  if (ext == ".fbx") {
    // Assimp keeps FBX coordinates in file units and reports the unit as centimetres per unit.
    double cm_per_unit = 1.0;
    if (scene.mMetaData != nullptr) {
      float f = 0.0f;
      double d = 0.0;
      if (scene.mMetaData->Get("UnitScaleFactor", d) && d > 0.0)
        cm_per_unit = d;
      else if (scene.mMetaData->Get("UnitScaleFactor", f) && f > 0.0f)
        cm_per_unit = f;
    }
    return 10.0 * cm_per_unit;
  }
  return 1.0;
}

struct SceneGatherer {
  const aiScene& scene;
  TriMesh mesh;
  std::unordered_map<PositionKey, Index, PositionKeyHash> vertex_of_position;
  std::unordered_map<PositionKey, Index, PositionKeyHash> index_of_uv;
  std::vector<Vec3> normal_sum;
  std::vector<int> normal_count;
  std::vector<Vec4> color_sum;
  std::vector<int> color_count;
  bool any_uvs = false;
  std::vector<unsigned> triangles_per_material;

  Index weld(const Vec3& p) {
    const auto [it, inserted] = vertex_of_position.try_emplace(key_of(p), static_cast<Index>(mesh.positions.size()));
    if (inserted) {
      mesh.positions.push_back(p);
      normal_sum.push_back(Vec3::Zero());
      normal_count.push_back(0);
      color_sum.push_back(Vec4::Zero());
      color_count.push_back(0);
    }
    return it->second;
  }

  Index uv_index(double u, double v) {
    const auto [it, inserted] = index_of_uv.try_emplace(key_of(Vec3(u, v, 0.0)), static_cast<Index>(mesh.uvs.size()));
    if (inserted) mesh.uvs.emplace_back(u, v);
    return it->second;
  }

  void add_mesh(const aiMesh& m, const Mat4& transform) {
    const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
    const Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    std::vector<Index> welded(m.mNumVertices);
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& a = m.mVertices[v];
      const Vec3 p = linear * Vec3(a.x, a.y, a.z) + transform.topRightCorner<3, 1>();
      const Index w = weld(p);
      welded[v] = w;
      if (m.mNormals != nullptr) {
        const aiVector3D& n = m.mNormals[v];
        const Vec3 nn = normal_matrix * Vec3(n.x, n.y, n.z);
        if (nn.allFinite() && nn.norm() > 0.0) {
          normal_sum[w] += nn.normalized();
          ++normal_count[w];
        }
      }
      if (m.mColors[0] != nullptr) {
        const aiColor4D& c = m.mColors[0][v];
        color_sum[w] += Vec4(c.r, c.g, c.b, c.a);
        ++color_count[w];
      }
    }
    const bool has_uvs = m.mTextureCoords[0] != nullptr;
    if (has_uvs && !any_uvs) {
      // Earlier meshes had no UVs: give their corners one shared (0, 0).
      any_uvs = true;
      const Index zero = uv_index(0.0, 0.0);
      mesh.triangle_uvs.assign(mesh.triangles.size(), Tri{zero, zero, zero});
    }
    if (m.mMaterialIndex >= triangles_per_material.size()) triangles_per_material.resize(m.mMaterialIndex + 1, 0);
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      Tri t{}, tuv{};
      bool valid = true;
      for (int c = 0; c < 3; ++c) {
        const unsigned i = face.mIndices[c];
        if (i >= m.mNumVertices) {
          valid = false;
          break;
        }
        t[c] = welded[i];
        if (has_uvs) tuv[c] = uv_index(m.mTextureCoords[0][i].x, m.mTextureCoords[0][i].y);
      }
      if (!valid) throw InputError("", "triangle " + std::to_string(f), "vertex index out of range");
      mesh.triangles.push_back(t);
      if (any_uvs) {
        if (!has_uvs) {
          const Index zero = uv_index(0.0, 0.0);
          tuv = Tri{zero, zero, zero};
        }
        mesh.triangle_uvs.push_back(tuv);
      }
      ++triangles_per_material[m.mMaterialIndex];
    }
  }

  void visit(const aiNode& node, const Mat4& parent) {
    const Mat4 transform = parent * to_mat4(node.mTransformation);
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const unsigned index = node.mMeshes[i];
      if (index < scene.mNumMeshes && scene.mMeshes[index] != nullptr) add_mesh(*scene.mMeshes[index], transform);
    }
    for (unsigned i = 0; i < node.mNumChildren; ++i) {
      if (node.mChildren[i] != nullptr) visit(*node.mChildren[i], transform);
    }
  }

  void finish() {
    const bool any_normals = std::any_of(normal_count.begin(), normal_count.end(), [](int n) { return n > 0; });
    if (any_normals) {
      mesh.normals.resize(mesh.positions.size());
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const double length = normal_sum[v].norm();
        mesh.normals[v] = length > 0.0 ? Vec3(normal_sum[v] / length) : Vec3(0.0, 0.0, 1.0);
      }
    }
    const bool any_colors = std::any_of(color_count.begin(), color_count.end(), [](int n) { return n > 0; });
    if (any_colors) {
      mesh.colors.resize(mesh.positions.size());
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        mesh.colors[v] =
            color_count[v] > 0 ? Vec4f((color_sum[v] / color_count[v]).cast<float>()) : Vec4f(1.0f, 1.0f, 1.0f, 1.0f);
      }
    }
  }
};

/// Reads one texture slot; embedded textures ("*0" or a name matching an embedded texture) go to
/// `embedded`, file textures come back as paths resolved against `folder`.
std::string texture_of(const aiScene& scene, const aiMaterial& material, aiTextureType type, const std::string& role,
                       const std::filesystem::path& folder, std::vector<EmbeddedTexture>& embedded) {
  if (material.GetTextureCount(type) == 0) return {};
  aiString name;
  if (material.GetTexture(type, 0, &name) != aiReturn_SUCCESS || name.length == 0) return {};
  const std::string reference(name.C_Str());
  if (const aiTexture* texture = scene.GetEmbeddedTexture(reference.c_str()); texture != nullptr) {
    EmbeddedTexture e;
    e.role = role;
    e.format = lower(std::string(texture->achFormatHint, strnlen(texture->achFormatHint, HINTMAXTEXTURELEN)));
    if (texture->mHeight == 0 && texture->pcData != nullptr) {  // compressed: mWidth bytes
      e.bytes.assign(reinterpret_cast<const char*>(texture->pcData), texture->mWidth);
      embedded.push_back(std::move(e));
    }
    return {};
  }
  std::filesystem::path p(reference);
  if (p.is_relative()) p = folder / p;
  return p.lexically_normal().string();
}

Material material_of(const aiScene& scene, const aiMaterial& m, const std::filesystem::path& folder,
                     std::vector<EmbeddedTexture>& embedded) {
  Material out;
  aiString name;
  if (m.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS) out.name = name.C_Str();
  aiColor4D color;
  if (m.Get(AI_MATKEY_BASE_COLOR, color) == aiReturn_SUCCESS ||
      m.Get(AI_MATKEY_COLOR_DIFFUSE, color) == aiReturn_SUCCESS) {
    out.base_color = Vec4f(color.r, color.g, color.b, color.a);
    float opacity = 1.0f;
    if (m.Get(AI_MATKEY_OPACITY, opacity) == aiReturn_SUCCESS && opacity < 1.0f) out.base_color[3] = opacity;
  }
  float value = 0.0f;
  if (m.Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == aiReturn_SUCCESS) out.roughness = std::clamp(value, 0.0f, 1.0f);
  if (m.Get(AI_MATKEY_METALLIC_FACTOR, value) == aiReturn_SUCCESS) out.metallic = std::clamp(value, 0.0f, 1.0f);
  out.base_color_texture = texture_of(scene, m, aiTextureType_BASE_COLOR, "base_color", folder, embedded);
  if (m.GetTextureCount(aiTextureType_BASE_COLOR) == 0)
    out.base_color_texture = texture_of(scene, m, aiTextureType_DIFFUSE, "base_color", folder, embedded);
  out.normal_texture = texture_of(scene, m, aiTextureType_NORMALS, "normal", folder, embedded);
  // glTF's metallic-roughness map arrives as aiTextureType_UNKNOWN (AI_MATKEY_GLTF_..._TEXTURE).
  out.roughness_texture = texture_of(scene, m, aiTextureType_UNKNOWN, "roughness", folder, embedded);
  if (m.GetTextureCount(aiTextureType_UNKNOWN) == 0)
    out.roughness_texture = texture_of(scene, m, aiTextureType_DIFFUSE_ROUGHNESS, "roughness", folder, embedded);
  return out;
}

}  // namespace

double mm_per_unit(const std::string& unit) {
  const std::string u = lower(unit);
  if (u == "m") return 1000.0;
  if (u == "cm") return 10.0;
  if (u == "mm") return 1.0;
  if (u == "in") return 25.4;
  throw InputError("mesh import options", "unit", "unknown unit '" + unit + "' (expected auto, m, cm, mm or in)");
}

ImportedMesh import_mesh_with_textures(const std::filesystem::path& path, const MeshImportOptions& options) {
  const std::string source = path.string();
  const std::string unit = lower(options.unit);
  require_input(std::isfinite(options.scale) && options.scale >= 0.0, "mesh import options", "scale",
                "must be a finite number >= 0");
  if (unit != "auto" && options.scale <= 0.0) (void)mm_per_unit(unit);  // reject unknown units before reading

  const std::string ply_bytes = check_mesh_file(path);

  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = nullptr;
  constexpr unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  try {
    scene = ply_bytes.empty() ? importer.ReadFile(source, flags)
                              : importer.ReadFileFromMemory(ply_bytes.data(), ply_bytes.size(), flags, "ply");
  } catch (const std::exception& e) {
    throw InputError(source, "", std::string("Assimp failed: ") + e.what());
  }
  if (scene == nullptr) throw InputError(source, "", importer.GetErrorString());
  require_input(scene->mRootNode != nullptr && (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) == 0, source, "",
                "the file holds no complete scene");

  ImportedMesh result;
  SceneGatherer gatherer{*scene, {}, {}, {}, {}, {}, {}, {}, false, {}};
  try {
    gatherer.visit(*scene->mRootNode, Mat4::Identity());
  } catch (const InputError& e) {
    throw InputError(source, e.location(), e.problem());
  }
  gatherer.finish();
  TriMesh& mesh = gatherer.mesh;
  require_input(!mesh.triangles.empty(), source, "", "the file holds no triangles");

  const std::string ext = lower(path.extension().string());
  result.mm_per_unit =
      options.scale > 0.0 ? options.scale : (unit == "auto" ? auto_mm_per_unit(ext, *scene) : mm_per_unit(unit));
  for (Vec3& p : mesh.positions) p *= result.mm_per_unit;

  const auto& counts = gatherer.triangles_per_material;
  if (!counts.empty()) {
    const auto best = static_cast<unsigned>(std::max_element(counts.begin(), counts.end()) - counts.begin());
    if (best < scene->mNumMaterials && scene->mMaterials[best] != nullptr) {
      mesh.material =
          material_of(*scene, *scene->mMaterials[best], std::filesystem::absolute(path).parent_path(), result.textures);
    }
  }

  mesh.validate(source);
  const double diagonal = bounding_box(mesh.positions).diagonal();
  if (diagonal < 20.0 || diagonal > 5000.0) {
    spdlog::warn(
        "{}: bounding-box diagonal is {:.4g} mm after scaling by {} mm per unit; is the unit right? "
        "(use the unit or scale option)",
        source, diagonal, result.mm_per_unit);
  }
  result.mesh = std::move(mesh);
  return result;
}

TriMesh import_mesh(const std::filesystem::path& path, const MeshImportOptions& options) {
  return import_mesh_with_textures(path, options).mesh;
}

}  // namespace forensim
