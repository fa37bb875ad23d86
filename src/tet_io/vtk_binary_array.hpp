#pragma once
/// Binary data arrays of VTK XML files (the layout ParaView's vtkXMLDataParser reads).
///
/// Uncompressed: one header word holding the byte count, then the bytes. Compressed with
/// vtkZLibDataCompressor: header words [#blocks, uncompressed block size, uncompressed size of the last
/// block (0 when it is full), compressed size of each block...], then the zlib streams of the blocks.
/// Header words are UInt32 or UInt64 (the file's header_type attribute). Inline ("binary") arrays are base64:
/// header and bytes encoded together when uncompressed, separately when compressed (as VTK writes them).
/// Data are little-endian, as on every platform forensim runs on.

#include <cstdint>
#include <string>
#include <string_view>

namespace forensim {

/// Header word size of a VTK XML file.
enum class VtkHeaderType { uint32, uint64 };

/// Uncompressed block size VTK uses (32 KiB).
constexpr std::size_t vtk_zlib_block_size = 32768;

/// Header and payload of one encoded array.
struct VtkEncodedArray {
  std::string header;   ///< header words
  std::string payload;  ///< raw bytes, or the concatenated zlib streams
};

/// Encodes `bytes`; compresses in vtk_zlib_block_size blocks with zlib level `zlib_level` (1..9) when
/// `compress`. Throws IoError (source "zlib") if zlib fails, or when a size does not fit a UInt32 header.
VtkEncodedArray encode_vtk_array(std::string_view bytes, VtkHeaderType header_type, bool compress, int zlib_level = 6);
/// Base64 text of an encoded array as VTK writes it inline.
std::string vtk_array_to_base64(const VtkEncodedArray& array, bool compressed);

/// Decodes the array that starts at `bytes[0]` (appended raw data: `bytes` runs to the end of the appended
/// block) into exactly `expected_size` bytes. Checks every header word against `expected_size` and against
/// the bytes available before allocating. Throws InputError(source, "byte <base_offset + n>", problem) for
/// truncated data, wrong byte counts, bad block headers or corrupt zlib streams.
std::string decode_vtk_array(std::string_view bytes, VtkHeaderType header_type, bool compressed,
                             std::size_t expected_size, const std::string& source, std::size_t base_offset);
/// Decodes the array that starts at `text[0]` of base64-encoded appended data (<AppendedData
/// encoding="base64">; offsets count characters), finding where it ends from its own header. Errors as
/// decode_vtk_base64_array.
std::string decode_vtk_appended_base64(std::string_view text, VtkHeaderType header_type, bool compressed,
                                       std::size_t expected_size, const std::string& source,
                                       const std::string& location);
/// Decodes inline base64 text (whitespace allowed anywhere) of one array into exactly `expected_size`
/// bytes. Errors as decode_vtk_array, located at the data array's `location` (e.g. "line 12").
std::string decode_vtk_base64_array(std::string_view text, VtkHeaderType header_type, bool compressed,
                                    std::size_t expected_size, const std::string& source, const std::string& location);

}  // namespace forensim
