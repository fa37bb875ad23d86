#pragma once
/// Reading tetrahedral (and triangle) meshes back from VTK XML UnstructuredGrid (.vtu) files: what write_vtu writes and
/// the same layouts from ParaView/VTK (versions 0.1, 1.0 and 2.x).

#include <filesystem>
#include <string>
#include <string_view>

#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Reads a single-piece .vtu of tetrahedra (VTK_TETRA, type 10). Supported: format="ascii",
/// format="binary" (inline base64) and format="appended" with <AppendedData encoding="raw"> or "base64"
/// (VTK's default); header_type UInt32 or UInt64 (UInt32 when absent, as in version 0.1); no compressor or
/// vtkZLibDataCompressor; little-endian; any integer or floating DataArray type. Point and cell arrays with 1 component
/// become scalar fields, with 3 components vector fields; the integer cell array "label" becomes tet_labels. Rejected
/// with InputError(path, "line N" or "byte N", problem): other cell types, several pieces, big-endian data, other
/// compressors (LZ4, LZMA), arrays with other component counts, and every malformed input (counts not matching the
/// data, truncated or corrupt blocks, bad base64, non-finite points, NaN fields, indices out of range). Throws IoError
/// when the file cannot be read.
TetMesh read_vtu(const std::filesystem::path& path);
/// read_vtu on file contents already in memory; `source` names them in errors.
TetMesh parse_vtu(std::string_view bytes, const std::string& source);

/// Reads a single-piece .vtu of triangles (VTK_TRIANGLE, type 5), e.g. a skin written by write_vtu(TriMesh),
/// in the same layouts and with the same checks as read_vtu: vertex order is kept, the point array "Normals"
/// becomes the normals, the integer cell array "label" the triangle labels, other arrays fields.
TriMesh read_vtu_surface(const std::filesystem::path& path);
/// read_vtu_surface on file contents already in memory.
TriMesh parse_vtu_surface(std::string_view bytes, const std::string& source);

}  // namespace forensim
