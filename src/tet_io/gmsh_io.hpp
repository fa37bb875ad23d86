#pragma once
/// Gmsh MSH files: exchange of labelled tetrahedral meshes with Gmsh (https://gmsh.info, "MSH file
/// format" in the Gmsh reference manual).
///
/// Label convention. forensim tet labels (TissueLabel) travel as physical groups of volume entities:
/// write_gmsh puts each label in its own volume entity with its own physical group, named "flesh" (label
/// 0), "bone" (label 1) or "region_<n>" (label n). read_gmsh maps a tet to the physical group of its volume
/// entity (the first one when an entity has several): a group named "flesh", "bone" or "region_<n>" gives
/// that label back, any other group gives its physical tag; a tet whose entity has no physical group gets
/// the entity tag (MSH 2.2: the elementary tag). Gmsh's reference tet is positively oriented in forensim's
/// sense, so node order is kept as is.

#include <filesystem>
#include <string>
#include <string_view>

#include "geometry/tet_mesh.hpp"

namespace forensim {

/// Reads a Gmsh mesh: MSH 4.1 ASCII or binary (little-endian, data size 8) or MSH 2.2 ASCII. Sections
/// $MeshFormat, $PhysicalNames, $Entities, $Nodes and $Elements are read, other sections skipped. Only
/// linear tets (element type 4) are kept; every other element type (points, lines, triangles, quadratic
/// elements...) is skipped. Node tags may be sparse and in any order: nodes become 0-based indices in file
/// order, tets are ordered by element tag. $NodeData/$ElementData views with 1 or 3 components that give a
/// value for every node (every tet) become vertex (tet) scalar or vector fields named after the view (the last
/// time step wins); partial views, other component counts and data on skipped elements are ignored.
/// Throws IoError when the file cannot be read and InputError(path, "line N" or "byte N", problem) for a
/// malformed, truncated or unsupported file (MSH 4.0, 2.2 binary, big-endian binary, undefined node tags,
/// non-finite coordinates, counts that do not fit the file).
TetMesh read_gmsh(const std::filesystem::path& path);
/// read_gmsh on file contents already in memory (an upload, a test); `source` names them in errors.
TetMesh parse_gmsh(std::string_view bytes, const std::string& source);

/// Writes `mesh` as MSH 4.1 (ASCII, or binary when `binary`), atomically. Positions are written exactly
/// (shortest round-trip decimal in ASCII, IEEE doubles in binary); node tags are 1..#V in index order and
/// element tags 1..#T in tet order, so read_gmsh restores indices and order exactly. One volume entity and
/// one physical group per distinct label (see the label convention above). Every vertex and tet field is
/// written as a $NodeData/$ElementData view (time 0) that Gmsh displays; '"' in field names becomes '\''.
/// Throws InputError when `mesh` fails validate(), IoError when the file cannot be written.
void write_gmsh(const std::filesystem::path& path, const TetMesh& mesh, bool binary = false);

}  // namespace forensim
