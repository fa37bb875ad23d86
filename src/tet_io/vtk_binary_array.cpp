#include "tet_io/vtk_binary_array.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/base64.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

/// Deflate cannot expand data by more than 1032:1; zlib adds a 2-byte header and a 4-byte checksum.
constexpr std::uint64_t max_zlib_ratio = 1032;

std::size_t word_size(VtkHeaderType type) {
  return type == VtkHeaderType::uint64 ? 8 : 4;
}

void append_word(std::string& out, VtkHeaderType type, std::uint64_t value) {
  if (type == VtkHeaderType::uint64) {
    char bytes[8];
    std::memcpy(bytes, &value, 8);
    out.append(bytes, 8);
  } else {
    if (value > UINT32_MAX) throw IoError("VTK array", "size does not fit a UInt32 header; use header type UInt64");
    const auto v32 = static_cast<std::uint32_t>(value);
    char bytes[4];
    std::memcpy(bytes, &v32, 4);
    out.append(bytes, 4);
  }
}

std::uint64_t word_at(std::string_view bytes, std::size_t offset, VtkHeaderType type) {
  if (type == VtkHeaderType::uint64) {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + offset, 8);
    return v;
  }
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

class ArrayDecoder {
 public:
  ArrayDecoder(std::string_view bytes, VtkHeaderType type, const std::string& source, std::size_t base)
      : m_bytes(bytes), m_type(type), m_word(word_size(type)), m_source(source), m_base(base) {}

  [[noreturn]] void fail(std::size_t at, const std::string& problem) const {
    throw InputError(m_source, "byte " + std::to_string(m_base + at), problem);
  }

  std::uint64_t word(std::size_t index) const {
    const std::size_t at = index * m_word;
    if (at + m_word > m_bytes.size()) fail(at, "truncated binary array header");
    return word_at(m_bytes, at, m_type);
  }

  std::string uncompressed(std::size_t expected) const {
    const std::uint64_t size = word(0);
    if (size != expected) {
      fail(0, "binary array holds " + std::to_string(size) + " bytes, expected " + std::to_string(expected));
    }
    if (size > m_bytes.size() - m_word) {
      fail(m_word, "truncated binary array: " + std::to_string(size) + " bytes declared, " +
                       std::to_string(m_bytes.size() - m_word) + " present");
    }
    return std::string(m_bytes.substr(m_word, size));
  }

  std::string compressed(std::size_t expected) const {
    const std::uint64_t blocks = word(0);
    const std::uint64_t block_size = word(1);
    const std::uint64_t last_size = word(2);
    if (blocks > (m_bytes.size() / m_word))
      fail(0, "compressed block count " + std::to_string(blocks) + " is too large");
    const std::size_t header_bytes = static_cast<std::size_t>(3 + blocks) * m_word;
    if (header_bytes > m_bytes.size()) fail(0, "truncated compression header");
    if (blocks > 0 && (block_size == 0 || last_size > block_size)) fail(m_word, "bad compression block sizes");
    // Total uncompressed size, without overflow: (blocks - 1) full blocks plus the last one.
    std::uint64_t total = 0;
    if (blocks > 0) {
      const std::uint64_t last = last_size == 0 ? block_size : last_size;
      if (block_size > 0 && blocks - 1 > (UINT64_MAX - last) / block_size) fail(0, "compressed size overflows");
      total = (blocks - 1) * block_size + last;
    }
    if (total != expected) {
      fail(0, "compressed array holds " + std::to_string(total) + " bytes, expected " + std::to_string(expected));
    }
    std::string out;
    std::vector<unsigned char> buffer;
    std::size_t at = header_bytes;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t compressed_size = word(3 + static_cast<std::size_t>(b));
      const std::uint64_t size = (b + 1 == blocks && last_size != 0) ? last_size : block_size;
      if (compressed_size > m_bytes.size() - at) {
        fail(at, "truncated compressed block " + std::to_string(b) + ": " + std::to_string(compressed_size) +
                     " bytes declared, " + std::to_string(m_bytes.size() - at) + " present");
      }
      if (size > max_zlib_ratio * compressed_size + 64) {
        fail(at, "compressed block " + std::to_string(b) + " claims an impossible compression ratio");
      }
      buffer.resize(static_cast<std::size_t>(size));
      uLongf produced = static_cast<uLongf>(size);
      const int status = ::uncompress(buffer.data(), &produced, reinterpret_cast<const Bytef*>(m_bytes.data() + at),
                                      static_cast<uLong>(compressed_size));
      if (status != Z_OK || produced != size) {
        fail(at, "corrupt zlib data in block " + std::to_string(b) + " (" +
                     (status == Z_OK ? "wrong size" : std::string(zError(status))) + ")");
      }
      out.append(reinterpret_cast<const char*>(buffer.data()), buffer.size());
      at += static_cast<std::size_t>(compressed_size);
    }
    return out;
  }

 private:
  std::string_view m_bytes;
  VtkHeaderType m_type;
  std::size_t m_word;
  const std::string& m_source;
  std::size_t m_base;
};

}  // namespace

VtkEncodedArray encode_vtk_array(std::string_view bytes, VtkHeaderType header_type, bool compress, int zlib_level) {
  VtkEncodedArray out;
  if (!compress) {
    append_word(out.header, header_type, bytes.size());
    out.payload = std::string(bytes);
    return out;
  }
  const std::size_t blocks = (bytes.size() + vtk_zlib_block_size - 1) / vtk_zlib_block_size;
  append_word(out.header, header_type, blocks);
  append_word(out.header, header_type, vtk_zlib_block_size);
  append_word(out.header, header_type, bytes.size() % vtk_zlib_block_size);
  std::vector<Bytef> buffer(compressBound(vtk_zlib_block_size));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = b * vtk_zlib_block_size;
    const std::size_t size = std::min(vtk_zlib_block_size, bytes.size() - begin);
    uLongf produced = static_cast<uLongf>(buffer.size());
    const int status = ::compress2(buffer.data(), &produced, reinterpret_cast<const Bytef*>(bytes.data() + begin),
                                   static_cast<uLong>(size), std::clamp(zlib_level, 1, 9));
    if (status != Z_OK) throw IoError("zlib", std::string("compression failed: ") + zError(status));
    append_word(out.header, header_type, produced);
    out.payload.append(reinterpret_cast<const char*>(buffer.data()), produced);
  }
  return out;
}

std::string vtk_array_to_base64(const VtkEncodedArray& array, bool compressed) {
  if (compressed) return base64_encode(array.header) + base64_encode(array.payload);
  return base64_encode(array.header + array.payload);
}

std::string decode_vtk_array(std::string_view bytes, VtkHeaderType header_type, bool compressed,
                             std::size_t expected_size, const std::string& source, std::size_t base_offset) {
  const ArrayDecoder decoder(bytes, header_type, source, base_offset);
  return compressed ? decoder.compressed(expected_size) : decoder.uncompressed(expected_size);
}

std::string decode_vtk_base64_array(std::string_view text, VtkHeaderType header_type, bool compressed,
                                    std::size_t expected_size, const std::string& source, const std::string& location) {
  std::string clean;
  clean.reserve(text.size());
  for (char c : text) {
    if (c != ' ' && c != '\n' && c != '\r' && c != '\t') clean += c;
  }
  auto decode = [&](std::string_view chunk, std::size_t chunk_offset) {
    std::size_t bad = 0;
    auto bytes = base64_decode(chunk, bad);
    if (!bytes) {
      throw InputError(source, location,
                       "bad base64 data at character " + std::to_string(chunk_offset + bad) + " of the array");
    }
    return std::move(*bytes);
  };
  std::string bytes;
  if (!compressed) {
    bytes = decode(clean, 0);
  } else {
    // The compression header is its own base64 chunk; its first three words give its length.
    const std::size_t word = word_size(header_type);
    const std::size_t first = base64_length(3 * word);
    if (clean.size() < first) throw InputError(source, location, "truncated compression header");
    const std::string start = decode(std::string_view(clean).substr(0, first), 0);
    const std::uint64_t blocks = word_at(start, 0, header_type);
    if (blocks > clean.size() / word) throw InputError(source, location, "compressed block count is too large");
    const std::size_t header_chars = base64_length((3 + static_cast<std::size_t>(blocks)) * word);
    if (header_chars > clean.size()) throw InputError(source, location, "truncated compression header");
    bytes = decode(std::string_view(clean).substr(0, header_chars), 0);
    bytes.resize((3 + static_cast<std::size_t>(blocks)) * word);  // drop padding bytes of the header chunk
    bytes += decode(std::string_view(clean).substr(header_chars), header_chars);
  }
  try {
    return decode_vtk_array(bytes, header_type, compressed, expected_size, source, 0);
  } catch (const InputError& e) {
    throw InputError(source, location, e.problem() + " (in the decoded base64 data)");
  }
}

std::string decode_vtk_appended_base64(std::string_view text, VtkHeaderType header_type, bool compressed,
                                       std::size_t expected_size, const std::string& source,
                                       const std::string& location) {
  const std::size_t word = word_size(header_type);
  auto decode_prefix = [&](std::size_t chars) {
    if (chars > text.size()) throw InputError(source, location, "truncated base64 appended data");
    std::size_t bad = 0;
    auto bytes = base64_decode(text.substr(0, chars), bad);
    if (!bytes) throw InputError(source, location, "bad base64 data at character " + std::to_string(bad));
    return std::move(*bytes);
  };
  std::size_t chars = 0;
  if (!compressed) {
    // Header and data form one base64 stream: the header word gives its length.
    const std::uint64_t size = word_at(decode_prefix(base64_length(word)), 0, header_type);
    if (size > text.size()) throw InputError(source, location, "truncated base64 appended data");
    chars = base64_length(word + static_cast<std::size_t>(size));
  } else {
    // The compression header is its own chunk, then the blocks as one chunk.
    const std::uint64_t blocks = word_at(decode_prefix(base64_length(3 * word)), 0, header_type);
    if (blocks > text.size() / word) throw InputError(source, location, "compressed block count is too large");
    const std::size_t header_chars = base64_length((3 + static_cast<std::size_t>(blocks)) * word);
    const std::string header = decode_prefix(header_chars);
    std::uint64_t payload = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      payload += word_at(header, (3 + b) * word, header_type);
      if (payload > text.size()) throw InputError(source, location, "truncated base64 appended data");
    }
    chars = header_chars + base64_length(static_cast<std::size_t>(payload));
  }
  if (chars > text.size()) throw InputError(source, location, "truncated base64 appended data");
  return decode_vtk_base64_array(text.substr(0, chars), header_type, compressed, expected_size, source, location);
}

}  // namespace forensim
