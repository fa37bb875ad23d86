#pragma once
/// Voxel data as volume files store it: element types, byte order, raw/gzip/text encodings, and reading a
/// block of voxels from a (part of a) data file with every size checked against the bytes really present
/// before anything is allocated. Shared by the NRRD and MetaImage readers.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace forensim {

/// Most data files one volume header may name (a numbered pattern or a LIST); far above any real slice count.
inline constexpr std::int64_t k_max_data_files = std::int64_t{1} << 16;

/// Element type of stored voxels.
enum class VoxelType { int8, uint8, int16, uint16, int32, uint32, int64, uint64, float32, float64 };

/// Bytes per stored voxel.
std::size_t voxel_type_size(VoxelType type);
/// Lower-case name ("uint16", "float32").
const char* voxel_type_name(VoxelType type);

/// How a data block is encoded on disk.
enum class VoxelEncoding {
  raw,   ///< the voxels' bytes
  gzip,  ///< a gzip or zlib stream (detected from its header) of the voxels' bytes; concatenated members allowed
  text,  ///< whitespace/comma separated decimal numbers
};

/// Converts `count` stored voxels at `bytes` to float (`big_endian` = byte order of the data).
void decode_voxels(const unsigned char* bytes, std::size_t count, VoxelType type, bool big_endian, float* out);

/// Where one block of voxels lives in a file.
struct VoxelBlockSource {
  std::filesystem::path file;  ///< the data file
  std::string source;          ///< name for errors (the header file, for detached data)
  std::uint64_t offset = 0;    ///< bytes before the block's region (an attached header's length)
  VoxelEncoding encoding = VoxelEncoding::raw;
  std::int64_t line_skip = 0;  ///< text lines to skip (on the file's bytes, before decompression)
  std::int64_t byte_skip = 0;  ///< bytes to skip (after decompression for gzip); -1 = the data ends the file (raw)
};

/// Upper bound on how many voxels of `type` the source can hold, from the file's size alone (deflate cannot
/// expand more than about 1032:1; text needs at least two characters per value). Throws IoError when the file is
/// missing and InputError for a negative skip other than -1. Call it for every block before allocating.
std::uint64_t max_voxels_available(const VoxelBlockSource& block, VoxelType type);

/// Reads exactly `count` voxels of the block into `out` (which must hold `count` floats). Throws InputError naming
/// the source, the data file and expected vs. actual bytes when the data is short, and for corrupt compressed
/// data or unparsable text; IoError when the file cannot be read.
void read_voxel_block(const VoxelBlockSource& block, VoxelType type, bool big_endian, std::size_t count, float* out);

/// Inflates a gzip or zlib stream (header detected) that must produce at least `expected` bytes; returns the first
/// `expected` bytes. `source` names the input for errors. Checks the ratio before allocating.
std::string inflate_exactly(std::string_view compressed, std::size_t expected, const std::string& source);
/// Deflates bytes as gzip (`gzip_header` true) or zlib.
std::string deflate_bytes(std::string_view bytes, bool gzip_header);

/// Expands a printf-style file-name pattern holding one integer conversion ("quarter.%d", "slice%03d.raw") for
/// `number`. Throws InputError naming `source` when the pattern has no or more than one conversion, or other '%'.
std::string format_file_pattern(const std::string& pattern, std::int64_t number, const std::string& source);

}  // namespace forensim
