#pragma once
/// Surface mesh import through Assimp (OBJ, PLY, STL, glTF/GLB, FBX and the other formats Assimp reads):
/// scanned heads, CT iso-surfaces exported from other tools, artists' meshes from Blender/Houdini/Unreal.
/// The result is a welded forensim TriMesh in millimetres with corner-indexed UVs.

#include <filesystem>
#include <string>
#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// How to turn file units into forensim's millimetres.
struct MeshImportOptions {
  /// "auto", "m", "cm", "mm" or "in". "auto": metres for glTF/GLB (the glTF spec's unit), the unit Assimp
  /// reports for FBX (UnitScaleFactor, centimetres by default), millimetres for OBJ, PLY, STL and the rest.
  std::string unit = "auto";
  /// Millimetres per file unit; when > 0 it overrides `unit`.
  double scale = 0.0;
};

/// A texture stored inside the mesh file (GLB, FBX with embedded media), as its encoded bytes.
struct EmbeddedTexture {
  std::string role;    ///< "base_color", "normal" or "roughness" (glTF metallic-roughness map)
  std::string format;  ///< encoded format hint from the file: "png", "jpg", ... (lower case)
  std::string bytes;   ///< the encoded image file (PNG, JPEG, ...) exactly as stored
};

/// A mesh with the textures that were embedded in its file.
struct ImportedMesh {
  TriMesh mesh;
  std::vector<EmbeddedTexture> textures;  ///< embedded textures; their Material paths are left empty
  double mm_per_unit = 1.0;               ///< scale that was applied to the file's coordinates
};

/// Millimetres per unit for a unit name ("m", "cm", "mm", "in"). Throws InputError for other names.
double mm_per_unit(const std::string& unit);

/// Reads every mesh of the file's scene into one welded TriMesh, in millimetres:
/// - node transforms are applied, polygons are triangulated, points and lines are dropped;
/// - vertices with exactly equal positions are merged (Assimp splits them at UV/normal seams), so the
///   topology can be checked; normals of merged vertices are averaged and renormalised, colours averaged;
/// - texture coordinates (channel 0, v up) become corner-indexed `uvs` + `triangle_uvs`;
/// - the material is that of the mesh with most triangles: base colour, roughness, metallic and texture
///   paths resolved against the mesh file's folder.
/// Hostile files are rejected before Assimp sees them (see check_mesh_file). Throws IoError when the file
/// cannot be read, InputError(path, location, problem) when it is malformed, when Assimp fails (with
/// Assimp's message), when it has no triangles or holds non-finite values. Logs a warning when the
/// bounding-box diagonal is below 20 mm or above 5 m (probably a wrong unit).
TriMesh import_mesh(const std::filesystem::path& path, const MeshImportOptions& options = {});

/// As import_mesh, also returning the encoded bytes of textures embedded in the file (GLB).
ImportedMesh import_mesh_with_textures(const std::filesystem::path& path, const MeshImportOptions& options = {});

}  // namespace forensim
