#pragma once
/// MetaImage volumes (ITK/VTK MetaIO, https://itk.org/Wiki/ITK/MetaIO/Documentation): a text header (.mhd) with a
/// separate data file, or header and data in one file (.mha). ITK and 3D Slicer write them; coordinates are LPS.

#include <filesystem>

#include "volume/scalar_grid.hpp"

namespace forensim {

/// Reads a 2-D or 3-D single-channel MetaImage into a grid in LPS mm with float values. Keys (case-insensitive):
/// ObjectType, NDims, DimSize, ElementType (MET_CHAR/UCHAR/SHORT/USHORT/INT/UINT/LONG/ULONG (32-bit as MetaIO
/// defines them)/LONG_LONG/ULONG_LONG/FLOAT/DOUBLE), ElementSpacing (else ElementSize), Offset (or Origin/Position),
/// TransformMatrix (or Rotation/Orientation: nine numbers, the i, j and k axis directions one after another, as ITK
/// reads them), BinaryData (False = text values), BinaryDataByteOrderMSB (or ElementByteOrderMSB), CompressedData
/// (zlib or gzip stream), HeaderSize (bytes to skip in the data file; -1 = the data ends the file),
/// ElementNumberOfChannels (must be 1) and ElementDataFile, last: LOCAL (data follows the header), a file name
/// (relative to the header's folder; a name ending in .gz is read as gzip), `LIST [<subdim>]` followed by one file
/// name per line, or `<pattern with %d> <min> <max> <step> [<subdim>]`. AnatomicalOrientation is ignored: MetaIO's
/// coordinates are LPS by ITK's convention. Throws InputError naming the file and line, IoError when unreadable.
ScalarGrid read_metaimage(const std::filesystem::path& path);

/// Writes a grid as MET_FLOAT little-endian MetaImage. A `.mha` path holds header and data (ElementDataFile LOCAL);
/// another extension (.mhd) gets a data file beside it, `<stem>.raw` or, with `compress`, `<stem>.zraw` (zlib,
/// CompressedData True). Written atomically; round-trips exactly through read_metaimage.
void write_metaimage(const std::filesystem::path& path, const ScalarGrid& grid, bool compress = false);

}  // namespace forensim
