#pragma once
/// NRRD volumes (teem's "Nearly Raw Raster Data", http://teem.sourceforge.net/nrrd/format.html), as 3D Slicer and
/// many research archives store CT scans: attached headers (.nrrd) and detached headers (.nhdr) with one data
/// file, a numbered file pattern or a LIST of files.

#include <filesystem>

#include "volume/scalar_grid.hpp"

namespace forensim {

/// Reads a 2-D or 3-D scalar NRRD into a grid in LPS mm with float values.
/// Supported: magic NRRD0001..NRRD0005; `type` int8/uint8/int16/uint16/int32/uint32/int64/uint64/float/double (all
/// of teem's spellings); `encoding` raw, gzip (gz), text (txt, ascii); `endian`; `sizes`; `space` (RAS and LAS are
/// converted to LPS by negating the affected axes; LPS, scanner-xyz and 3D-right/left-handed are taken as LPS),
/// `space dimension` 3, `space directions` (spacing = vector length), `space origin`, `spacings` (used when there
/// are no space directions); `byte skip` (-1 = data ends the file, raw only), `line skip`; `data file` as a name,
/// as `<pattern with %d> <min> <max> <step> [<subdim>]` or as `LIST [<subdim>]` followed by one file name per
/// line (names relative to the header's folder; each file's data is subdim-dimensional, default dimension-1, and
/// byte/line skips apply to every file). Other fields and key:=value pairs are ignored.
/// Throws InputError naming the file and the field's line for anything malformed (sizes vs. available bytes are
/// checked before allocating), IoError when a file cannot be read.
ScalarGrid read_nrrd(const std::filesystem::path& path);

/// Writes a grid as float32 little-endian NRRD (NRRD0004, space left-posterior-superior, space directions and
/// origin, raw or gzip). A `.nhdr` path gets a detached header and a data file beside it named
/// `<stem>.raw` or `<stem>.raw.gz`; any other extension an attached header. Both files are written atomically.
/// Values, spacing, origin and direction round-trip exactly through read_nrrd.
void write_nrrd(const std::filesystem::path& path, const ScalarGrid& grid, bool gzip = true);

}  // namespace forensim
