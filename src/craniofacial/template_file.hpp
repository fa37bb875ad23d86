#pragma once
/// A template head on disk: everything the reconstruction needs of a template (Kähler, Haber and Seidel 2003,
/// section 4.1) in one file, so a template built once (`forensim template build`, from a user's head mesh or CT)
/// is used by every later `forensim reconstruct --template FILE`.
///
/// Format: CBOR (RFC 8949) of one map, written and read through nlohmann::json:
///   format "forensim-template", version 1, source (what it was built from);
///   skin, skull: meshes as maps of binary little-endian arrays (positions, normals and uvs as float64 triples or
///     pairs, triangles and triangle_uvs as int32 triples);
///   triangle_chart (int32 per skin triangle), chart_names, uv_l2_stretch, uv_overlap_free;
///   landmarks: [{bone, skin, skull, skull_normal, skin_point, depth_mm, midline}];
///   skin_landmarks: [{name, position}]; muscles: [{name, kind, fibres, samples, thickness_mm, grid}];
///   texture_png: the skin's own base-colour map (PNG bytes) or absent (procedural skin maps are made).
/// Any CBOR viewer opens it. Reading checks everything a hostile file could get wrong (the tag, the version, keys
/// it does not know, array lengths, indices, finite numbers, the landmark names' vocabulary) and throws naming the
/// file and the field.

#include <filesystem>
#include <string>

#include "craniofacial/template_head.hpp"

namespace forensim {

/// File version written; read_template_head accepts it only.
inline constexpr int kTemplateFileVersion = 1;

/// The template as CBOR bytes (see the file comment).
std::string encode_template_head(const TemplateHead& head);

/// The template from CBOR bytes; `source` names them in errors. Throws InputError for anything malformed.
TemplateHead decode_template_head(const std::string& bytes, const std::string& source);

/// Writes `head` to `path` atomically (a temporary name, then a rename). Throws IoError.
void write_template_head(const std::filesystem::path& path, const TemplateHead& head);

/// Reads a template written by write_template_head. Throws IoError when the file cannot be read, InputError naming
/// the file and the field when its content is malformed.
TemplateHead read_template_head(const std::filesystem::path& path);

}  // namespace forensim
