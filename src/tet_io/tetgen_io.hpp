#pragma once
/// TetGen .node/.ele files: exchange of tetrahedral meshes with TetGen (https://wias-berlin.de/software/tetgen,
/// "File Formats" in the TetGen 1.6 manual).
///
/// .node: `<#nodes> 3 <#attributes> <0|1 boundary markers>`, then `<index> x y z [attributes] [marker]`.
/// .ele:  `<#tets> <4|10 nodes per tet> <#attributes>`, then `<index> n0 n1 n2 n3 [n4..n9] [attributes]`.
/// '#' starts a comment anywhere on a line; indices start at 0 or 1 (the first node's index decides, as in
/// TetGen). Field convention: node attributes become vertex scalar fields, the boundary marker the vertex
/// field "boundary_marker"; the first .ele attribute (TetGen's region attribute) is the tet label and any
/// further ones tet scalar fields. Attribute names travel in a comment line that write_tetgen adds
/// ("# forensim attributes: moisture displacement.x displacement.y displacement.z"); without it they are
/// named "attribute_<i>" / "tet_attribute_<i>". Names "<n>.x", "<n>.y", "<n>.z" in a row form a vector field.

#include <filesystem>
#include <string>
#include <string_view>

#include "geometry/tet_mesh.hpp"

namespace forensim {

/// Reads `<base>.node` and `<base>.ele`, where `node_or_ele_or_basename` is either file or the common base
/// name without extension. Quadratic tets (10 nodes) keep their 4 corners. Node and tet order are kept;
/// indices become 0-based. Throws IoError when a file cannot be read, InputError(file, "line N", problem)
/// for a malformed file (bad counts, non-finite values, indices out of range or not consecutive,
/// non-integral region attributes, fewer lines than declared).
TetMesh read_tetgen(const std::filesystem::path& node_or_ele_or_basename);
/// read_tetgen on the contents of the two files already in memory; the sources name them in errors.
TetMesh parse_tetgen(std::string_view node_bytes, std::string_view ele_bytes, const std::string& node_source,
                     const std::string& ele_source);

/// Writes `<basename>.node` and `<basename>.ele` (each atomically), 1-based like TetGen's own output; a
/// `basename` ending in .node or .ele names the pair too.
/// Positions and fields are written exactly (shortest round-trip decimals). Vertex scalar and vector fields
/// become node attributes (a vertex field "boundary_marker" with integral values becomes the boundary
/// marker column instead); the tet label is the region attribute, followed by tet scalar and vector fields.
/// Throws InputError when `mesh` fails validate(), IoError when a file cannot be written.
void write_tetgen(const std::filesystem::path& basename, const TetMesh& mesh);

}  // namespace forensim
