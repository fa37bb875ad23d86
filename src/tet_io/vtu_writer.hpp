#pragma once
/// VTK XML UnstructuredGrid (.vtu) output for ParaView: desiccation results (moisture, displacement,
/// shrinkage per node or tet) on the tet mesh, or data on a skin triangle mesh. Format: "VTK File Formats",
/// XML section (https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html), written as VTK 9 does:
/// version 1.0, LittleEndian, header_type UInt64 (or UInt32), optional vtkZLibDataCompressor.

#include <filesystem>

#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"
#include "tet_io/vtk_binary_array.hpp"

namespace forensim {

/// How data arrays are stored.
enum class VtuEncoding {
  ascii,          ///< format="ascii": decimal text (exact: shortest round-trip digits); largest, readable
  inline_base64,  ///< format="binary": base64 inside each DataArray element
  appended_raw,   ///< format="appended" with <AppendedData encoding="raw">: smallest and fastest
};

/// Floating-point type of written real arrays.
enum class VtuPrecision { float64, float32 };

struct VtuOptions {
  VtuEncoding encoding = VtuEncoding::appended_raw;
  bool compress = false;  ///< zlib-compress binary arrays (vtkZLibDataCompressor); ignored for ascii
  int zlib_level = 6;     ///< 1 (fast) .. 9 (small)
  VtuPrecision point_precision = VtuPrecision::float64;  ///< type of the Points array
  VtuPrecision field_precision = VtuPrecision::float64;  ///< type of scalar and vector field arrays
  VtkHeaderType header_type = VtkHeaderType::uint64;     ///< binary header word size
};

/// Writes `mesh` atomically as a .vtu of VTK_TETRA cells (type 10). PointData: every vertex field (scalars
/// with 1 component, vectors with 3). CellData: "label" (Int32, mesh.label(t) for every tet) and every tet
/// field. Connectivity and offsets are Int64, types UInt8. Throws InputError when `mesh` fails validate() or
/// a tet field is named "label", IoError when the file cannot be written.
void write_vtu(const std::filesystem::path& path, const TetMesh& mesh, const VtuOptions& options = {});

/// Writes `mesh` atomically as a .vtu of VTK_TRIANGLE cells (type 5). PointData: vertex fields and, when
/// present, "Normals" (3 components); CellData: "label" (Int32) when triangle_labels is not empty, and every
/// triangle field. Throws like the tet version.
void write_vtu(const std::filesystem::path& path, const TriMesh& mesh, const VtuOptions& options = {});

}  // namespace forensim
