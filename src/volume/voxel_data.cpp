#include "volume/voxel_data.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

#include "core/error.hpp"

namespace forensim {
namespace {

template <typename T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

template <typename T>
void decode_as(const unsigned char* bytes, std::size_t count, bool swap, float* out) {
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(load<T>(bytes + i * sizeof(T), swap));
}

std::uint64_t file_size_or_throw(const std::filesystem::path& file, const std::string& source) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(file, ec);
  if (ec) {
    if (!std::filesystem::exists(file)) {
      throw InputError(source, "data file", "data file '" + file.string() + "' does not exist");
    }
    throw IoError(file.string(), "cannot get the size: " + ec.message());
  }
  return size;
}

std::string read_range(const std::filesystem::path& file, std::uint64_t offset, std::uint64_t length) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError(file.string(), "cannot open for reading");
  in.seekg(static_cast<std::streamoff>(offset));
  std::string bytes(length, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(length));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw IoError(file.string(), "read failed");
  return bytes;
}

std::string where(const VoxelBlockSource& block) {
  return "data file '" + block.file.string() + "'";
}

}  // namespace

std::size_t voxel_type_size(VoxelType type) {
  switch (type) {
    case VoxelType::int8:
    case VoxelType::uint8:
      return 1;
    case VoxelType::int16:
    case VoxelType::uint16:
      return 2;
    case VoxelType::int32:
    case VoxelType::uint32:
    case VoxelType::float32:
      return 4;
    case VoxelType::int64:
    case VoxelType::uint64:
    case VoxelType::float64:
      return 8;
  }
  return 1;
}

const char* voxel_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::int8:
      return "int8";
    case VoxelType::uint8:
      return "uint8";
    case VoxelType::int16:
      return "int16";
    case VoxelType::uint16:
      return "uint16";
    case VoxelType::int32:
      return "int32";
    case VoxelType::uint32:
      return "uint32";
    case VoxelType::int64:
      return "int64";
    case VoxelType::uint64:
      return "uint64";
    case VoxelType::float32:
      return "float32";
    case VoxelType::float64:
      return "float64";
  }
  return "?";
}

void decode_voxels(const unsigned char* bytes, std::size_t count, VoxelType type, bool big_endian, float* out) {
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  switch (type) {
    case VoxelType::int8:
      decode_as<std::int8_t>(bytes, count, swap, out);
      break;
    case VoxelType::uint8:
      decode_as<std::uint8_t>(bytes, count, swap, out);
      break;
    case VoxelType::int16:
      decode_as<std::int16_t>(bytes, count, swap, out);
      break;
    case VoxelType::uint16:
      decode_as<std::uint16_t>(bytes, count, swap, out);
      break;
    case VoxelType::int32:
      decode_as<std::int32_t>(bytes, count, swap, out);
      break;
    case VoxelType::uint32:
      decode_as<std::uint32_t>(bytes, count, swap, out);
      break;
    case VoxelType::int64:
      decode_as<std::int64_t>(bytes, count, swap, out);
      break;
    case VoxelType::uint64:
      decode_as<std::uint64_t>(bytes, count, swap, out);
      break;
    case VoxelType::float32:
      decode_as<float>(bytes, count, swap, out);
      break;
    case VoxelType::float64:
      decode_as<double>(bytes, count, swap, out);
      break;
  }
}

std::uint64_t max_voxels_available(const VoxelBlockSource& block, VoxelType type) {
  const std::uint64_t size = file_size_or_throw(block.file, block.source);
  require_input(block.line_skip >= 0, block.source, "line skip",
                "is negative (" + std::to_string(block.line_skip) + ")");
  require_input(block.byte_skip >= -1, block.source, "byte skip",
                "is negative (" + std::to_string(block.byte_skip) + "; only -1 is allowed)");
  require_input(block.byte_skip != -1 || block.encoding == VoxelEncoding::raw, block.source, "byte skip",
                "-1 is only allowed with raw encoding");
  const std::uint64_t region = size > block.offset ? size - block.offset : 0;
  const std::uint64_t element = voxel_type_size(type);
  switch (block.encoding) {
    case VoxelEncoding::raw: {
      const std::uint64_t skip = block.byte_skip > 0 ? std::uint64_t(block.byte_skip) : 0;
      return region > skip ? (region - skip) / element : 0;
    }
    case VoxelEncoding::gzip:
      return (region * 1100 + 4096) / element;
    case VoxelEncoding::text:
      return (region + 1) / 2;
  }
  return 0;
}

std::string inflate_exactly(std::string_view compressed, std::size_t expected, const std::string& source) {
  require_input(expected <= compressed.size() * std::uint64_t{1100} + 4096, source, "compressed data",
                "declares " + std::to_string(expected) + " bytes, more than " + std::to_string(compressed.size()) +
                    " compressed bytes can hold");
  std::string out(expected, '\0');
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error("zlib: inflateInit2 failed");
  std::size_t in_pos = 0, out_pos = 0;
  int rc = Z_OK;
  while (out_pos < expected) {
    const std::size_t in_chunk = std::min<std::size_t>(compressed.size() - in_pos, 1u << 30);
    const std::size_t out_chunk = std::min<std::size_t>(expected - out_pos, 1u << 30);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + in_pos));
    zs.avail_in = static_cast<uInt>(in_chunk);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + out_pos);
    zs.avail_out = static_cast<uInt>(out_chunk);
    rc = inflate(&zs, Z_NO_FLUSH);
    in_pos += in_chunk - zs.avail_in;
    out_pos += out_chunk - zs.avail_out;
    if (rc == Z_STREAM_END) {
      // Concatenated gzip members continue the data.
      if (out_pos < expected && in_pos < compressed.size()) {
        inflateReset(&zs);
        continue;
      }
      break;
    }
    if (rc != Z_OK) {
      const std::string msg = zs.msg != nullptr ? zs.msg : "error " + std::to_string(rc);
      inflateEnd(&zs);
      throw InputError(source, "compressed byte " + std::to_string(in_pos), "corrupt compressed data: " + msg);
    }
    if (zs.avail_in == 0 && in_pos >= compressed.size() && out_pos < expected) break;  // input exhausted
  }
  inflateEnd(&zs);
  if (out_pos < expected) {
    throw InputError(source, "compressed data",
                     "expected " + std::to_string(expected) + " bytes after decompression, got " +
                         std::to_string(out_pos) + (rc == Z_STREAM_END ? "" : " (stream truncated)"));
  }
  return out;
}

std::string deflate_bytes(std::string_view bytes, bool gzip_header) {
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, gzip_header ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw Error("zlib: deflateInit2 failed");
  }
  std::string out(deflateBound(&zs, static_cast<uLong>(bytes.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  zs.avail_in = static_cast<uInt>(bytes.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  const std::size_t produced = zs.total_out;
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw Error("zlib: deflate failed");
  out.resize(produced);
  return out;
}

void read_voxel_block(const VoxelBlockSource& block, VoxelType type, bool big_endian, std::size_t count, float* out) {
  const std::uint64_t size = file_size_or_throw(block.file, block.source);
  const std::size_t element = voxel_type_size(type);
  const std::uint64_t needed = std::uint64_t(count) * element;
  (void)max_voxels_available(block, type);  // validates the skips
  std::uint64_t start = std::min(block.offset, size);

  std::string bytes;
  if (block.line_skip > 0) {
    // Skip lines on the file's bytes; the rest of the file is read (bounded by its real size).
    bytes = read_range(block.file, start, size - start);
    std::size_t pos = 0;
    for (std::int64_t l = 0; l < block.line_skip; ++l) {
      const std::size_t nl = bytes.find('\n', pos);
      if (nl == std::string::npos) {
        throw InputError(block.source, "line skip",
                         where(block) + " has fewer than " + std::to_string(block.line_skip) + " lines to skip");
      }
      pos = nl + 1;
    }
    bytes.erase(0, pos);
  }
  const bool have_bytes = block.line_skip > 0;

  switch (block.encoding) {
    case VoxelEncoding::raw: {
      const std::uint64_t available = have_bytes ? bytes.size() : size - start;
      std::uint64_t skip = 0;
      if (block.byte_skip == -1) {
        skip = available >= needed ? available - needed : 0;
      } else {
        skip = std::uint64_t(block.byte_skip);
      }
      const std::uint64_t after_skip = available > skip ? available - skip : 0;
      if (after_skip < needed) {
        throw InputError(block.source, where(block),
                         "expected " + std::to_string(needed) + " bytes of " + voxel_type_name(type) + " data (" +
                             std::to_string(count) + " voxels) after skipping " + std::to_string(skip) +
                             " bytes, found " + std::to_string(after_skip));
      }
      if (have_bytes) {
        decode_voxels(reinterpret_cast<const unsigned char*>(bytes.data() + skip), count, type, big_endian, out);
      } else {
        const std::string data = read_range(block.file, start + skip, needed);
        if (data.size() != needed) throw IoError(block.file.string(), "short read");
        decode_voxels(reinterpret_cast<const unsigned char*>(data.data()), count, type, big_endian, out);
      }
      return;
    }
    case VoxelEncoding::gzip: {
      if (!have_bytes) bytes = read_range(block.file, start, size - start);
      const std::uint64_t skip = block.byte_skip > 0 ? std::uint64_t(block.byte_skip) : 0;
      const std::string data = inflate_exactly(bytes, skip + needed, block.source + " (" + where(block) + ")");
      decode_voxels(reinterpret_cast<const unsigned char*>(data.data() + skip), count, type, big_endian, out);
      return;
    }
    case VoxelEncoding::text: {
      if (!have_bytes) bytes = read_range(block.file, start, size - start);
      const std::uint64_t skip = block.byte_skip > 0 ? std::uint64_t(block.byte_skip) : 0;
      std::size_t pos = std::min<std::uint64_t>(skip, bytes.size());
      std::size_t line = 1;
      for (std::size_t v = 0; v < count; ++v) {
        while (pos < bytes.size() && (std::isspace(static_cast<unsigned char>(bytes[pos])) || bytes[pos] == ',')) {
          if (bytes[pos] == '\n') ++line;
          ++pos;
        }
        if (pos >= bytes.size()) {
          throw InputError(block.source, where(block) + " line " + std::to_string(line),
                           "expected " + std::to_string(count) + " text values, found " + std::to_string(v));
        }
        double value = 0.0;
        const char* first = bytes.data() + pos;
        const char* last = bytes.data() + bytes.size();
        if (*first == '+') ++first;
        const auto [ptr, ec] = std::from_chars(first, last, value);
        if (ec == std::errc::result_out_of_range) {
          value = (*first == '-') ? -HUGE_VAL : HUGE_VAL;
        } else if (ec != std::errc()) {
          const std::size_t len = std::min<std::size_t>(16, bytes.size() - pos);
          throw InputError(block.source, where(block) + " line " + std::to_string(line),
                           "value " + std::to_string(v) + " is not a number: '" + bytes.substr(pos, len) + "'");
        }
        out[v] = static_cast<float>(value);
        pos = static_cast<std::size_t>(ptr - bytes.data());
      }
      return;
    }
  }
}

std::string format_file_pattern(const std::string& pattern, std::int64_t number, const std::string& source) {
  std::string out;
  int conversions = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    // %[0][width]d (also i, u)
    std::size_t j = i + 1;
    bool zero = false;
    if (j < pattern.size() && pattern[j] == '0') {
      zero = true;
      ++j;
    }
    int width = 0;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && width < 100) {
      width = width * 10 + (pattern[j] - '0');
      ++j;
    }
    require_input(j < pattern.size() && (pattern[j] == 'd' || pattern[j] == 'i' || pattern[j] == 'u') && width <= 32,
                  source, "data file", "file name pattern '" + pattern + "' has an unsupported '%' conversion");
    std::string digits = std::to_string(number < 0 ? -number : number);
    if (static_cast<int>(digits.size()) < width - (number < 0 ? 1 : 0)) {
      digits.insert(0, std::size_t(width - (number < 0 ? 1 : 0)) - digits.size(), zero ? '0' : ' ');
    }
    out += (number < 0 ? "-" : "") + digits;
    ++conversions;
    i = j;
  }
  require_input(conversions == 1, source, "data file",
                "file name pattern '" + pattern + "' must hold exactly one integer conversion such as %d");
  return out;
}

}  // namespace forensim
