#include "volume/metaimage_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "volume/header_text.hpp"
#include "volume/voxel_data.hpp"

namespace forensim {
namespace {

using Field = HeaderField;

std::optional<VoxelType> meta_type(const std::string& name) {
  static const std::map<std::string, VoxelType> types = {
      {"met_char", VoxelType::int8},         {"met_uchar", VoxelType::uint8},   {"met_short", VoxelType::int16},
      {"met_ushort", VoxelType::uint16},     {"met_int", VoxelType::int32},     {"met_uint", VoxelType::uint32},
      {"met_long", VoxelType::int32},        {"met_ulong", VoxelType::uint32},  {"met_long_long", VoxelType::int64},
      {"met_ulong_long", VoxelType::uint64}, {"met_float", VoxelType::float32}, {"met_double", VoxelType::float64},
  };
  const auto it = types.find(to_lower(trim(name)));
  if (it == types.end()) return std::nullopt;
  return it->second;
}

bool parse_bool(const Field& f, const std::string& src, const std::string& key) {
  const std::string v = to_lower(f.value);
  if (v == "true" || v == "1" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "no") return false;
  throw InputError(src, f.location(), key + " '" + f.value + "' is not True or False");
}

std::vector<double> parse_numbers(const Field& f, std::size_t n, const std::string& src, const std::string& key) {
  const std::vector<std::string> words = split_words(f.value);
  require_input(words.size() == n, src, f.location(),
                key + " lists " + std::to_string(words.size()) + " numbers, expected " + std::to_string(n));
  std::vector<double> out;
  for (const std::string& w : words) {
    const double v = parse_double(w, src, f.location(), key);
    require_input(std::isfinite(v), src, f.location(), key + " value '" + w + "' is not finite");
    out.push_back(v);
  }
  return out;
}

}  // namespace

ScalarGrid read_metaimage(const std::filesystem::path& path) {
  const std::string src = path.string();
  const HeaderText header = read_header_text(path, false, "ElementDataFile");
  std::map<std::string, Field> fields;
  for (const HeaderLine& line : header.lines) {
    const std::string text = trim(line.text);
    if (text.empty() || text[0] == '#') continue;
    const std::size_t eq = text.find('=');
    require_input(eq != std::string::npos, src, "line " + std::to_string(line.number),
                  "expected '<Key> = <value>', got '" + text.substr(0, 80) + "'");
    const std::string key = to_lower(trim(text.substr(0, eq)));
    fields[key] = {trim(text.substr(eq + 1)), line.number};
  }
  const auto field = [&](std::initializer_list<const char*> keys) -> const Field* {
    for (const char* k : keys) {
      const auto it = fields.find(k);
      if (it != fields.end()) return &it->second;
    }
    return nullptr;
  };
  const auto required = [&](const char* key) -> const Field& {
    const Field* f = field({key});
    require_input(f != nullptr, src, "header", std::string("required key '") + key + "' is missing");
    return *f;
  };

  if (const Field* f = field({"objecttype"})) {
    require_input(to_lower(f->value) == "image", src, f->location(), "ObjectType '" + f->value + "' is not Image");
  }
  const Field& ndims_field = required("ndims");
  const std::int64_t ndims = parse_int(ndims_field.value, src, ndims_field.location(), "NDims");
  require_input(ndims == 2 || ndims == 3, src, ndims_field.location(),
                "NDims " + std::to_string(ndims) + " is not supported (scalar volumes have 2 or 3 axes)");
  const std::size_t n = std::size_t(ndims);
  const Field& dim_field = required("dimsize");
  const std::vector<std::string> dim_words = split_words(dim_field.value);
  require_input(dim_words.size() == n, src, dim_field.location(),
                "DimSize lists " + std::to_string(dim_words.size()) + " numbers for NDims " + std::to_string(ndims));
  std::int64_t sizes[3] = {1, 1, 1};
  for (std::size_t a = 0; a < n; ++a) sizes[a] = parse_int(dim_words[a], src, dim_field.location(), "DimSize");
  const std::uint64_t count = checked_voxel_count(sizes, src, dim_field.location());

  const Field& type_field = required("elementtype");
  const std::optional<VoxelType> type = meta_type(type_field.value);
  require_input(type.has_value(), src, type_field.location(),
                "unsupported or unknown ElementType '" + type_field.value + "'");
  if (const Field* f = field({"elementnumberofchannels"})) {
    const std::int64_t channels = parse_int(f->value, src, f->location(), "ElementNumberOfChannels");
    require_input(channels == 1, src, f->location(),
                  "ElementNumberOfChannels " + std::to_string(channels) + " is not supported (scalar volumes only)");
  }
  const bool binary = field({"binarydata"}) == nullptr || parse_bool(*field({"binarydata"}), src, "BinaryData");
  bool big_endian = false;
  if (const Field* f = field({"binarydatabyteordermsb", "elementbyteordermsb"})) {
    big_endian = parse_bool(*f, src, "BinaryDataByteOrderMSB");
  }
  bool compressed = false;
  if (const Field* f = field({"compresseddata"})) compressed = parse_bool(*f, src, "CompressedData");

  ScalarGrid grid;
  grid.nx = int(sizes[0]);
  grid.ny = int(sizes[1]);
  grid.nz = int(sizes[2]);
  if (const Field* f = field({"elementspacing", "elementsize"})) {
    const std::vector<double> s = parse_numbers(*f, n, src, "ElementSpacing");
    for (std::size_t a = 0; a < n; ++a) {
      require_input(
          s[a] > 0.0, src, f->location(),
          "ElementSpacing of axis " + std::to_string(a) + " is not positive (" + fmt::format("{}", s[a]) + ")");
      grid.spacing[Eigen::Index(a)] = s[a];
    }
  }
  if (const Field* f = field({"offset", "origin", "position"})) {
    const std::vector<double> o = parse_numbers(*f, n, src, "Offset");
    for (std::size_t a = 0; a < n; ++a) grid.origin[Eigen::Index(a)] = o[a];
  }
  if (const Field* f = field({"transformmatrix", "rotation", "orientation"})) {
    const std::vector<double> m = parse_numbers(*f, n * n, src, "TransformMatrix");
    for (std::size_t a = 0; a < n; ++a) {
      Vec3 axis = Vec3::Zero();
      for (std::size_t b = 0; b < n; ++b) axis[Eigen::Index(b)] = m[a * n + b];
      require_input(axis.norm() > 1e-6, src, f->location(), "axis " + std::to_string(a) + " direction is zero");
      grid.direction.col(Eigen::Index(a)) = axis.normalized();
    }
    if (n == 2) grid.direction.col(2) = grid.direction.col(0).cross(grid.direction.col(1)).normalized();
    require_input(std::abs(grid.direction.determinant()) > 1e-6, src, f->location(), "axes are parallel");
  }
  std::int64_t header_size = 0;
  if (const Field* f = field({"headersize"})) {
    header_size = parse_int(f->value, src, f->location(), "HeaderSize");
    require_input(header_size >= -1, src, f->location(),
                  "HeaderSize " + std::to_string(header_size) + " is negative (only -1 is allowed)");
  }

  const Field& data_field = required("elementdatafile");
  const std::vector<std::string> words = split_words(data_field.value);
  require_input(!words.empty(), src, data_field.location(), "ElementDataFile is empty");
  VoxelEncoding encoding = !binary ? VoxelEncoding::text : compressed ? VoxelEncoding::gzip : VoxelEncoding::raw;
  require_input(header_size != -1 || encoding == VoxelEncoding::raw, src, "HeaderSize",
                "-1 is only allowed for uncompressed binary data");

  std::vector<std::filesystem::path> files;
  std::uint64_t offset = 0;
  std::int64_t subdim = ndims - 1;
  bool multi = false;
  const std::filesystem::path folder = path.parent_path();
  const auto read_subdim = [&](const std::string& word) {
    subdim = parse_int(word, src, data_field.location(), "ElementDataFile sub-dimension");
    require_input(subdim >= 1 && subdim <= ndims, src, data_field.location(),
                  "sub-dimension " + std::to_string(subdim) + " is outside [1, " + std::to_string(ndims) + "]");
  };
  if (to_lower(words[0]) == "local") {
    files.push_back(path);
    offset = header.data_offset;
  } else if (words[0] == "LIST") {
    require_input(words.size() <= 2, src, data_field.location(), "expected 'LIST [<subdim>]'");
    if (words.size() == 2) read_subdim(words[1]);
    const std::uint64_t size = std::filesystem::file_size(path);
    const std::string rest =
        read_file(path, std::size_t{64} << 20).substr(std::min<std::uint64_t>(header.data_offset, size));
    for (const std::string& name : split_words(rest)) {
      files.push_back(folder / name);
      require_input(std::int64_t(files.size()) <= k_max_data_files, src, data_field.location(),
                    "LIST names more than " + std::to_string(k_max_data_files) + " files");
    }
    multi = true;
  } else if (words.size() >= 4 && words[0].find('%') != std::string::npos) {
    require_input(words.size() <= 5, src, data_field.location(), "expected '<pattern> <min> <max> <step> [<subdim>]'");
    const std::int64_t lo = parse_int(words[1], src, data_field.location(), "ElementDataFile min");
    const std::int64_t hi = parse_int(words[2], src, data_field.location(), "ElementDataFile max");
    const std::int64_t step = parse_int(words[3], src, data_field.location(), "ElementDataFile step");
    if (words.size() == 5) read_subdim(words[4]);
    require_input(step != 0 && (hi - lo) / step >= 0 && std::abs(lo) < (std::int64_t{1} << 40) &&
                      std::abs(hi) < (std::int64_t{1} << 40),
                  src, data_field.location(), "file numbers do not form a range");
    const std::int64_t n_files = (hi - lo) / step + 1;
    require_input(std::uint64_t(n_files) <= count && n_files <= k_max_data_files, src, data_field.location(),
                  std::to_string(n_files) + " data files for " + std::to_string(count) +
                      " voxels (at most one file per voxel and " + std::to_string(k_max_data_files) + " files)");
    for (std::int64_t i = 0; i < n_files; ++i) {
      files.push_back(folder / format_file_pattern(words[0], lo + i * step, src + " " + data_field.location()));
    }
    multi = true;
  } else {
    files.push_back(folder / data_field.value);
    const std::string name = to_lower(data_field.value);
    if (binary && name.size() > 3 && name.substr(name.size() - 3) == ".gz") encoding = VoxelEncoding::gzip;
  }
  require_input(header_size != -1 || encoding == VoxelEncoding::raw, src, "HeaderSize",
                "-1 is only allowed for uncompressed binary data");
  std::uint64_t per_file = count;
  if (multi) {
    per_file = 1;
    for (std::int64_t a = 0; a < subdim; ++a) per_file *= std::uint64_t(sizes[a]);
    require_input(!files.empty() && per_file * files.size() == count, src, data_field.location(),
                  std::to_string(files.size()) + " data files of " + std::to_string(per_file) +
                      " voxels each do not make the " + std::to_string(count) + " voxels of DimSize");
  }
  std::vector<VoxelBlockSource> blocks;
  for (const auto& file : files) {
    VoxelBlockSource b;
    b.file = file;
    b.source = src;
    b.offset = offset;
    b.encoding = encoding;
    b.byte_skip = header_size;
    blocks.push_back(b);
  }
  for (const VoxelBlockSource& b : blocks) {
    const std::uint64_t available = max_voxels_available(b, *type);
    require_input(available >= per_file, src, "data file '" + b.file.string() + "'",
                  "expected " + std::to_string(per_file * voxel_type_size(*type)) + " bytes of " +
                      voxel_type_name(*type) + " data (" + std::to_string(per_file) +
                      " voxels), the file can hold at most " + std::to_string(available) + " voxels");
  }
  grid.values.resize(count);
  std::uint64_t done = 0;
  for (const VoxelBlockSource& b : blocks) {
    read_voxel_block(b, *type, big_endian, per_file, grid.values.data() + done);
    done += per_file;
  }
  grid.validate(src);
  return grid;
}

void write_metaimage(const std::filesystem::path& path, const ScalarGrid& grid, bool compress) {
  grid.validate("grid written to " + path.string());
  const bool local = to_lower(path.extension().string()) == ".mha";
  std::string data(grid.values.size() * sizeof(float), '\0');
  for (std::size_t i = 0; i < grid.values.size(); ++i) {
    unsigned char b[4];
    std::memcpy(b, &grid.values[i], 4);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + 4);
    std::memcpy(data.data() + 4 * i, b, 4);
  }
  if (compress) data = deflate_bytes(data, false);
  std::string header = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n";
  header += std::string("CompressedData = ") + (compress ? "True" : "False") + "\n";
  if (compress) header += fmt::format("CompressedDataSize = {}\n", data.size());
  header += "TransformMatrix =";
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) header += fmt::format(" {}", grid.direction(b, a));
  }
  header += fmt::format("\nOffset = {} {} {}\n", grid.origin[0], grid.origin[1], grid.origin[2]);
  header += "AnatomicalOrientation = RAI\n";
  header += fmt::format("ElementSpacing = {} {} {}\n", grid.spacing[0], grid.spacing[1], grid.spacing[2]);
  header += fmt::format("DimSize = {} {} {}\n", grid.nx, grid.ny, grid.nz);
  header += "ElementType = MET_FLOAT\n";
  if (local) {
    write_file_atomic(path, header + "ElementDataFile = LOCAL\n" + data);
  } else {
    const std::string data_name = path.stem().string() + (compress ? ".zraw" : ".raw");
    write_file_atomic(path.parent_path() / data_name, data);
    write_file_atomic(path, header + "ElementDataFile = " + data_name + "\n");
  }
}

}  // namespace forensim
