#pragma once
/// Triangle surface mesh: skins, skulls, scanned heads, iso-surfaces. Topology is welded (one vertex per
/// position), so closedness and manifoldness can be checked on it; texture coordinates are indexed per
/// triangle corner (like OBJ), so UV seams need no duplicated positions. Lengths are millimetres unless a
/// function says otherwise.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/field_set.hpp"

namespace forensim {

/// Surface appearance as the importers found it and the exporters write it (glTF PBR metallic-roughness).
struct Material {
  std::string name;
  Vec4f base_color{1.0f, 1.0f, 1.0f, 1.0f};  ///< linear RGBA multiplier
  float roughness = 0.6f;                    ///< [0,1]
  float metallic = 0.0f;                     ///< [0,1]
  std::string base_color_texture;            ///< file path (absolute, or relative to the mesh file), or empty
  std::string normal_texture;                ///< tangent-space normal map path, or empty
  std::string roughness_texture;             ///< path, or empty
};

struct TriMesh {
  std::vector<Vec3> positions;       ///< #V vertex positions
  std::vector<Tri> triangles;        ///< #F triangles, counter-clockwise when seen from outside
  std::vector<Vec3> normals;         ///< #V unit vertex normals, or empty
  std::vector<Vec2> uvs;             ///< #UV texture coordinates (u right, v up, as in OBJ and OpenGL), or empty
  std::vector<Tri> triangle_uvs;     ///< #F corner indices into uvs; empty when the mesh has no UVs
  std::vector<Vec4f> colors;         ///< #V linear RGBA vertex colours in [0,1], or empty
  std::vector<int> triangle_labels;  ///< #F region labels, or empty
  FieldSet vertex_fields;            ///< named per-vertex data
  FieldSet triangle_fields;          ///< named per-triangle data
  Material material;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool has_uvs() const { return !triangle_uvs.empty(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }

  /// Checks sizes, index ranges and finiteness of every array. Throws InputError naming `source`, the
  /// array and the first bad element.
  void validate(const std::string& source) const;
};

}  // namespace forensim
