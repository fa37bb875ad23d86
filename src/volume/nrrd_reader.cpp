#include "volume/nrrd_reader.hpp"

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

std::optional<VoxelType> nrrd_type(const std::string& name) {
  static const std::map<std::string, VoxelType> types = {
      {"signed char", VoxelType::int8},
      {"int8", VoxelType::int8},
      {"int8_t", VoxelType::int8},
      {"uchar", VoxelType::uint8},
      {"unsigned char", VoxelType::uint8},
      {"uint8", VoxelType::uint8},
      {"uint8_t", VoxelType::uint8},
      {"short", VoxelType::int16},
      {"short int", VoxelType::int16},
      {"signed short", VoxelType::int16},
      {"signed short int", VoxelType::int16},
      {"int16", VoxelType::int16},
      {"int16_t", VoxelType::int16},
      {"ushort", VoxelType::uint16},
      {"unsigned short", VoxelType::uint16},
      {"unsigned short int", VoxelType::uint16},
      {"uint16", VoxelType::uint16},
      {"uint16_t", VoxelType::uint16},
      {"int", VoxelType::int32},
      {"signed int", VoxelType::int32},
      {"int32", VoxelType::int32},
      {"int32_t", VoxelType::int32},
      {"uint", VoxelType::uint32},
      {"unsigned int", VoxelType::uint32},
      {"uint32", VoxelType::uint32},
      {"uint32_t", VoxelType::uint32},
      {"longlong", VoxelType::int64},
      {"long long", VoxelType::int64},
      {"long long int", VoxelType::int64},
      {"signed long long", VoxelType::int64},
      {"signed long long int", VoxelType::int64},
      {"int64", VoxelType::int64},
      {"int64_t", VoxelType::int64},
      {"ulonglong", VoxelType::uint64},
      {"unsigned long long", VoxelType::uint64},
      {"unsigned long long int", VoxelType::uint64},
      {"uint64", VoxelType::uint64},
      {"uint64_t", VoxelType::uint64},
      {"float", VoxelType::float32},
      {"double", VoxelType::float64},
  };
  const auto it = types.find(to_lower(trim(name)));
  if (it == types.end()) return std::nullopt;
  return it->second;
}

// Parses "(x,y,z)" into a vector; "none" gives nullopt.
std::optional<Vec3> parse_vector(const std::string& text, const std::string& source, const std::string& location,
                                 const std::string& what) {
  if (to_lower(trim(text)) == "none") return std::nullopt;
  const std::vector<std::string> parts = split_words(text, true);
  require_input(parts.size() == 3 && trim(text).front() == '(', source, location,
                what + " '" + text + "' is not a 3-D vector such as (1,0,0)");
  Vec3 v;
  for (int a = 0; a < 3; ++a) v[a] = parse_double(parts[std::size_t(a)], source, location, what + " component");
  require_input(v.allFinite(), source, location, what + " '" + text + "' is not finite");
  return v;
}

// Splits the value of "space directions" into its per-axis groups ("(1,0,0)", "none", ...).
std::vector<std::string> direction_groups(const std::string& text) {
  std::vector<std::string> groups;
  std::size_t i = 0;
  while (i < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[i]))) {
      ++i;
    } else if (text[i] == '(') {
      const std::size_t close = text.find(')', i);
      const std::size_t end = close == std::string::npos ? text.size() : close + 1;
      groups.push_back(text.substr(i, end - i));
      i = end;
    } else {
      std::size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
      groups.push_back(text.substr(i, end - i));
      i = end;
    }
  }
  return groups;
}

}  // namespace

ScalarGrid read_nrrd(const std::filesystem::path& path) {
  const std::string src = path.string();
  const HeaderText header = read_header_text(path, true, "");
  require_input(!header.lines.empty() && header.lines[0].text.rfind("NRRD000", 0) == 0 &&
                    header.lines[0].text.size() == 8 && header.lines[0].text[7] >= '1' &&
                    header.lines[0].text[7] <= '5',
                src, "line 1", "not a NRRD file (expected the magic NRRD0001..NRRD0005)");

  std::map<std::string, Field> fields;
  std::vector<std::string> list_files;
  bool in_list = false;
  for (std::size_t l = 1; l < header.lines.size(); ++l) {
    const HeaderLine& line = header.lines[l];
    if (in_list) {
      const std::string name = trim(line.text);
      if (!name.empty()) list_files.push_back(name);
      continue;
    }
    if (line.text.empty() || line.text[0] == '#') continue;
    if (line.text.find(":=") != std::string::npos) continue;  // key/value pair
    const std::size_t colon = line.text.find(": ");
    require_input(colon != std::string::npos, src, "line " + std::to_string(line.number),
                  "expected '<field>: <value>', got '" + line.text.substr(0, 80) + "'");
    std::string key = to_lower(trim(line.text.substr(0, colon)));
    if (key == "datafile") key = "data file";
    if (key == "byteskip") key = "byte skip";
    if (key == "lineskip") key = "line skip";
    require_input(fields.count(key) == 0, src, "line " + std::to_string(line.number), "field '" + key + "' repeats");
    fields[key] = {trim(line.text.substr(colon + 2)), line.number};
    if (key == "data file") {
      const std::vector<std::string> words = split_words(fields[key].value);
      if (!words.empty() && words[0] == "LIST") in_list = true;
    }
  }
  const auto field = [&](const std::string& key) -> const Field* {
    const auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };
  const auto required = [&](const std::string& key) -> const Field& {
    const Field* f = field(key);
    require_input(f != nullptr, src, "header", "required field '" + key + "' is missing");
    return *f;
  };

  // dimension and sizes
  const Field& dim_field = required("dimension");
  const std::int64_t dimension = parse_int(dim_field.value, src, dim_field.location(), "dimension");
  require_input(dimension == 2 || dimension == 3, src, dim_field.location(),
                "dimension " + std::to_string(dimension) + " is not supported (scalar volumes have 2 or 3 axes)");
  const Field& sizes_field = required("sizes");
  const std::vector<std::string> size_words = split_words(sizes_field.value);
  require_input(
      std::int64_t(size_words.size()) == dimension, src, sizes_field.location(),
      "sizes lists " + std::to_string(size_words.size()) + " numbers for dimension " + std::to_string(dimension));
  std::int64_t sizes[3] = {1, 1, 1};
  for (std::size_t a = 0; a < size_words.size(); ++a) {
    sizes[a] = parse_int(size_words[a], src, sizes_field.location(), "size");
  }
  const std::uint64_t count = checked_voxel_count(sizes, src, sizes_field.location());

  // type, encoding, endian
  const Field& type_field = required("type");
  const std::optional<VoxelType> type = nrrd_type(type_field.value);
  require_input(type.has_value(), src, type_field.location(), "unsupported or unknown type '" + type_field.value + "'");
  const Field& enc_field = required("encoding");
  const std::string enc = to_lower(enc_field.value);
  VoxelEncoding encoding;
  if (enc == "raw") {
    encoding = VoxelEncoding::raw;
  } else if (enc == "gzip" || enc == "gz") {
    encoding = VoxelEncoding::gzip;
  } else if (enc == "text" || enc == "txt" || enc == "ascii") {
    encoding = VoxelEncoding::text;
  } else {
    throw InputError(src, enc_field.location(), "unsupported or unknown encoding '" + enc_field.value + "'");
  }
  bool big_endian = false;
  if (const Field* f = field("endian")) {
    const std::string e = to_lower(f->value);
    require_input(e == "little" || e == "big", src, f->location(), "endian '" + f->value + "' is not little or big");
    big_endian = e == "big";
  } else {
    require_input(voxel_type_size(*type) == 1 || encoding == VoxelEncoding::text, src, "header",
                  "required field 'endian' is missing for multi-byte type " + std::string(voxel_type_name(*type)));
  }

  // geometry
  ScalarGrid grid;
  grid.nx = int(sizes[0]);
  grid.ny = int(sizes[1]);
  grid.nz = int(sizes[2]);
  Vec3 flip = Vec3::Ones();  // RAS -> LPS sign per world axis
  if (const Field* f = field("space")) {
    const std::string s = to_lower(f->value);
    if (s == "right-anterior-superior" || s == "ras") {
      flip = Vec3(-1, -1, 1);
    } else if (s == "left-anterior-superior" || s == "las") {
      flip = Vec3(1, -1, 1);
    } else if (s == "left-posterior-superior" || s == "lps" || s == "scanner-xyz" || s == "3d-right-handed" ||
               s == "3d-left-handed") {
      flip = Vec3::Ones();
    } else {
      throw InputError(src, f->location(), "unsupported space '" + f->value + "' (expected a 3-D space)");
    }
  }
  if (const Field* f = field("space dimension")) {
    const std::int64_t sd = parse_int(f->value, src, f->location(), "space dimension");
    require_input(sd == 3, src, f->location(), "space dimension " + std::to_string(sd) + " is not supported (need 3)");
  }
  if (const Field* f = field("space directions")) {
    const std::vector<std::string> groups = direction_groups(f->value);
    require_input(std::int64_t(groups.size()) == dimension, src, f->location(),
                  "space directions lists " + std::to_string(groups.size()) + " vectors for dimension " +
                      std::to_string(dimension));
    for (std::size_t a = 0; a < groups.size(); ++a) {
      const std::optional<Vec3> v = parse_vector(groups[a], src, f->location(), "space direction");
      require_input(v.has_value(), src, f->location(), "axis " + std::to_string(a) + " has no space direction");
      const double length = v->norm();
      require_input(length > 0.0, src, f->location(), "space direction of axis " + std::to_string(a) + " is zero");
      grid.spacing[Eigen::Index(a)] = length;
      grid.direction.col(Eigen::Index(a)) = v->cwiseProduct(flip) / length;
    }
  } else if (const Field* sp = field("spacings")) {
    const std::vector<std::string> words = split_words(sp->value);
    require_input(
        std::int64_t(words.size()) == dimension, src, sp->location(),
        "spacings lists " + std::to_string(words.size()) + " numbers for dimension " + std::to_string(dimension));
    for (std::size_t a = 0; a < words.size(); ++a) {
      const double s = parse_double(words[a], src, sp->location(), "spacing");
      require_input(std::isfinite(s) && s != 0.0, src, sp->location(),
                    "spacing '" + words[a] + "' of axis " + std::to_string(a) + " is not a non-zero finite number");
      // A negative spacing means the axis runs backwards.
      grid.spacing[Eigen::Index(a)] = std::abs(s);
      if (s < 0) grid.direction.col(Eigen::Index(a)) *= -1.0;
    }
    grid.direction = flip.asDiagonal() * grid.direction;
  }
  if (dimension == 2) grid.direction.col(2) = grid.direction.col(0).cross(grid.direction.col(1)).normalized();
  if (const Field* f = field("space origin")) {
    const std::optional<Vec3> o = parse_vector(f->value, src, f->location(), "space origin");
    require_input(o.has_value(), src, f->location(), "space origin must not be 'none'");
    grid.origin = o->cwiseProduct(flip);
  }
  require_input(std::abs(grid.direction.determinant()) > 1e-6, src, "space directions", "axes are parallel");
  for (int a = 0; a < 3; ++a) grid.direction.col(a).normalize();

  // skips
  std::int64_t byte_skip = 0, line_skip = 0;
  if (const Field* f = field("byte skip")) byte_skip = parse_int(f->value, src, f->location(), "byte skip");
  if (const Field* f = field("line skip")) line_skip = parse_int(f->value, src, f->location(), "line skip");
  require_input(line_skip >= 0, src, field("line skip") ? field("line skip")->location() : "line skip",
                "line skip " + std::to_string(line_skip) + " is negative");
  require_input(byte_skip >= -1, src, field("byte skip") ? field("byte skip")->location() : "byte skip",
                "byte skip " + std::to_string(byte_skip) + " is negative (only -1 is allowed)");
  require_input(byte_skip != -1 || encoding == VoxelEncoding::raw, src,
                field("byte skip") ? field("byte skip")->location() : "byte skip",
                "byte skip -1 is only allowed with raw encoding");

  // data blocks
  struct Block {
    VoxelBlockSource source;
    std::uint64_t voxels;
  };
  std::vector<Block> blocks;
  const std::filesystem::path folder = path.parent_path();
  const auto make_source = [&](const std::filesystem::path& file, std::uint64_t offset) {
    VoxelBlockSource s;
    s.file = file;
    s.source = src;
    s.offset = offset;
    s.encoding = encoding;
    s.line_skip = line_skip;
    s.byte_skip = byte_skip;
    return s;
  };
  const Field* data_field = field("data file");
  if (data_field == nullptr) {
    require_input(header.ended_by_blank_line, src, "header",
                  "no 'data file' field and no blank line ending the header before attached data");
    blocks.push_back({make_source(path, header.data_offset), count});
  } else {
    const std::vector<std::string> words = split_words(data_field->value);
    require_input(!words.empty(), src, data_field->location(), "data file is empty");
    std::vector<std::filesystem::path> files;
    std::int64_t subdim = dimension - 1;
    const auto read_subdim = [&](const std::string& word) {
      subdim = parse_int(word, src, data_field->location(), "data file sub-dimension");
      require_input(subdim >= 1 && subdim <= dimension, src, data_field->location(),
                    "sub-dimension " + std::to_string(subdim) + " is outside [1, " + std::to_string(dimension) + "]");
    };
    bool multi = false;
    if (words[0] == "LIST") {
      require_input(words.size() <= 2, src, data_field->location(), "expected 'LIST [<subdim>]'");
      if (words.size() == 2) read_subdim(words[1]);
      require_input(std::int64_t(list_files.size()) <= k_max_data_files, src, data_field->location(),
                    "LIST names more than " + std::to_string(k_max_data_files) + " files");
      for (const std::string& name : list_files) files.push_back(folder / name);
      multi = true;
    } else if (words.size() >= 4 && words[0].find('%') != std::string::npos) {
      require_input(words.size() <= 5, src, data_field->location(),
                    "expected '<pattern> <min> <max> <step> [<subdim>]'");
      const std::int64_t lo = parse_int(words[1], src, data_field->location(), "data file min");
      const std::int64_t hi = parse_int(words[2], src, data_field->location(), "data file max");
      const std::int64_t step = parse_int(words[3], src, data_field->location(), "data file step");
      if (words.size() == 5) read_subdim(words[4]);
      require_input(
          step != 0 && (hi - lo) / step >= 0 && std::abs(lo) < (std::int64_t{1} << 40) &&
              std::abs(hi) < (std::int64_t{1} << 40),
          src, data_field->location(),
          "data file numbers " + words[1] + " to " + words[2] + " in steps of " + words[3] + " do not form a range");
      const std::int64_t n_files = (hi - lo) / step + 1;
      require_input(std::uint64_t(n_files) <= count && n_files <= k_max_data_files, src, data_field->location(),
                    std::to_string(n_files) + " data files for " + std::to_string(count) +
                        " voxels (at most one file per voxel and " + std::to_string(k_max_data_files) + " files)");
      for (std::int64_t i = 0; i < n_files; ++i) {
        files.push_back(folder / format_file_pattern(words[0], lo + i * step, src + " " + data_field->location()));
      }
      multi = true;
    } else {
      files.push_back(folder / data_field->value);
    }
    std::uint64_t per_file = count;
    if (multi) {
      per_file = 1;
      for (std::int64_t a = 0; a < subdim; ++a) per_file *= std::uint64_t(sizes[a]);
      require_input(!files.empty() && per_file * files.size() == count, src, data_field->location(),
                    std::to_string(files.size()) + " data files of " + std::to_string(per_file) +
                        " voxels each do not make the " + std::to_string(count) + " voxels of sizes '" +
                        sizes_field.value + "'");
    }
    for (const auto& file : files) blocks.push_back({make_source(file, 0), per_file});
  }

  // Check every block against the bytes present before allocating.
  for (const Block& b : blocks) {
    const std::uint64_t available = max_voxels_available(b.source, *type);
    require_input(available >= b.voxels, src, "data file '" + b.source.file.string() + "'",
                  "expected " + std::to_string(b.voxels * voxel_type_size(*type)) + " bytes of " +
                      voxel_type_name(*type) + " data (" + std::to_string(b.voxels) +
                      " voxels), the file can hold at most " + std::to_string(available) + " voxels");
  }
  grid.values.resize(count);
  std::uint64_t done = 0;
  for (const Block& b : blocks) {
    read_voxel_block(b.source, *type, big_endian, b.voxels, grid.values.data() + done);
    done += b.voxels;
  }
  grid.validate(src);
  return grid;
}

void write_nrrd(const std::filesystem::path& path, const ScalarGrid& grid, bool gzip) {
  grid.validate("grid written to " + path.string());
  const bool detached = to_lower(path.extension().string()) == ".nhdr";
  std::string header = "NRRD0004\n# written by forensim\n";
  header += "type: float\ndimension: 3\nspace: left-posterior-superior\n";
  header += fmt::format("sizes: {} {} {}\n", grid.nx, grid.ny, grid.nz);
  header += "space directions:";
  for (int a = 0; a < 3; ++a) {
    const Vec3 v = grid.direction.col(a) * grid.spacing[a];
    header += fmt::format(" ({},{},{})", v[0], v[1], v[2]);
  }
  header += "\nkinds: domain domain domain\nendian: little\n";
  header += std::string("encoding: ") + (gzip ? "gzip" : "raw") + "\n";
  header += fmt::format("space origin: ({},{},{})\n", grid.origin[0], grid.origin[1], grid.origin[2]);

  std::string data(grid.values.size() * sizeof(float), '\0');
  for (std::size_t i = 0; i < grid.values.size(); ++i) {
    unsigned char b[4];
    std::memcpy(b, &grid.values[i], 4);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + 4);
    std::memcpy(data.data() + 4 * i, b, 4);
  }
  if (gzip) data = deflate_bytes(data, true);

  if (detached) {
    const std::string data_name = path.stem().string() + (gzip ? ".raw.gz" : ".raw");
    header += "data file: " + data_name + "\n";
    write_file_atomic(path.parent_path() / data_name, data);
    write_file_atomic(path, header);
  } else {
    write_file_atomic(path, header + "\n" + data);
  }
}

}  // namespace forensim
