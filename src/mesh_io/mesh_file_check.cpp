#include "mesh_io/mesh_file_check.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

constexpr std::uint64_t max_elements = static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max());

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// Reads up to `count` bytes from the start of the file.
std::string read_prefix(const std::filesystem::path& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading");
  std::string bytes(count, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

/// Bytes that the text formats here never hold: the C0 controls but tab, line feed and carriage return. Assimp's
/// parsers stop at a NUL and take a form feed for a line end but a vertical tab for neither space nor line end, so
/// text holding them reads differently there than here.
bool is_control_byte(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 9 || u == 11 || u == 12 || (u > 13 && u < 32);
}

// ---------------------------------------------------------------------------------------------- PLY

struct PlyProperty {
  int size = 0;        ///< bytes of a scalar, or of each list item
  int count_size = 0;  ///< bytes of the list length; 0 for scalars
  bool count_signed = false;
  bool face_indices = false;  ///< the vertex index list of element "face"
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t header_line = 0;
};

int ply_type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

bool ply_type_signed(std::string_view type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
}

bool ply_type_float(std::string_view type) {
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

/// Whether Assimp's PLY parser reads the item count of an element with this name; it reads 0 for any other.
bool is_assimp_ply_element(std::string_view name) {
  return name == "vertex" || name == "face" || name == "tristrips" || name == "edge" || name == "material";
}

/// Reads a binary integer of `size` bytes (1, 2 or 4) as the list length.
std::int64_t read_binary_count(const unsigned char* p, int size, bool is_signed, bool big_endian) {
  std::uint32_t v = 0;
  for (int b = 0; b < size; ++b) {
    const int shift = big_endian ? 8 * (size - 1 - b) : 8 * b;
    v |= static_cast<std::uint32_t>(p[b]) << shift;
  }
  if (!is_signed) return v;
  if (size == 1) return static_cast<std::int8_t>(v);
  if (size == 2) return static_cast<std::int16_t>(v);
  return static_cast<std::int32_t>(v);
}

/// A finite decimal number as PLY ASCII bodies hold and Assimp's parser accepts: optional sign, then a digit
/// or a point followed by a digit. (Assimp leaks memory when it meets anything else, so we reject it first.)
bool is_ply_number(std::string_view token) {
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) token.remove_prefix(1);
  if (token.empty()) return false;
  const bool starts_ok = std::isdigit(static_cast<unsigned char>(token[0])) ||
                         (token[0] == '.' && token.size() > 1 && std::isdigit(static_cast<unsigned char>(token[1])));
  if (!starts_ok) return false;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size() && std::isfinite(value);
}

[[noreturn]] void fail_element(const std::string& source, std::uint64_t at, const std::string& element,
                               std::uint64_t item, const std::string& problem) {
  std::string message = problem;
  message.append(" in element '").append(element).append("' ").append(std::to_string(item));
  throw InputError(source, "byte " + std::to_string(at), message);
}

// Assimp takes a face without indices for a polygon, and its triangulation then aborts the process on an
// internal assertion (found by fuzz/mesh_ply).
constexpr const char* face_without_indices = "a face has no vertex indices";

std::string check_ply(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::string bytes = read_file(path);
  // Header: text lines up to "end_header".
  const std::size_t header_limit = std::min<std::size_t>(bytes.size(), std::size_t{1} << 20);
  const std::size_t end = bytes.find("end_header", 0);
  require_input(bytes.compare(0, 3, "ply") == 0 && bytes.size() > 3 && (bytes[3] == '\n' || bytes[3] == '\r'), source,
                "byte 0", "not a PLY file (it does not start with 'ply')");
  require_input(end != std::string::npos && end < header_limit, source, "header",
                "no 'end_header' line in the first " + std::to_string(header_limit) + " bytes");
  std::size_t body = bytes.find('\n', end);
  require_input(body != std::string::npos, source, "header", "file ends right after 'end_header'");
  ++body;
  // A NUL or a carriage return inside a header line ends the line early for Assimp (found by fuzz/mesh_ply).
  const auto control = std::find_if(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(body), is_control_byte);
  require_input(control == bytes.begin() + static_cast<std::ptrdiff_t>(body), source,
                "byte " + std::to_string(control - bytes.begin()), "a control byte in the header");
  const auto require_no_lone_carriage_return = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = bytes.find('\r', from); i < to; i = bytes.find('\r', i + 1)) {
      require_input(i + 1 < bytes.size() && bytes[i + 1] == '\n', source, "byte " + std::to_string(i),
                    "a carriage return inside a line");
    }
  };
  require_no_lone_carriage_return(0, body);

  enum class Format { unknown, ascii, little, big } format = Format::unknown;
  std::vector<PlyElement> elements;
  std::size_t line_number = 0;
  bool header_ended = false;
  std::size_t pos = 0;
  while (pos < body) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos || eol > body) eol = body;
    const std::string_view line(bytes.data() + pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    const std::string location = "line " + std::to_string(line_number);
    const auto words = split_words(line);
    if (words.empty()) continue;
    if (words[0] == "format") {
      require_input(words.size() >= 2, source, location, "incomplete 'format' line");
      // Assimp keeps the first 'format' line, this check the last (found by fuzz/mesh_ply).
      require_input(format == Format::unknown, source, location, "a second 'format' line");
      if (words[1] == "ascii")
        format = Format::ascii;
      else if (words[1] == "binary_little_endian")
        format = Format::little;
      else if (words[1] == "binary_big_endian")
        format = Format::big;
      else
        throw InputError(source, location, "unknown PLY format '" + std::string(words[1]) + "'");
    } else if (words[0] == "element") {
      require_input(words.size() == 3, source, location, "'element' needs a name and a count");
      PlyElement e;
      e.name = std::string(words[1]);
      e.header_line = line_number;
      const auto [ptr, ec] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), e.count);
      require_input(ec == std::errc() && ptr == words[2].data() + words[2].size(), source, location,
                    "element count '" + std::string(words[2]) + "' is not a non-negative integer");
      require_input(e.count <= max_elements, source, location,
                    "element '" + e.name + "' declares " + std::to_string(e.count) + " items, more than 2^31 - 1");
      elements.push_back(std::move(e));
    } else if (words[0] == "property") {
      require_input(!elements.empty(), source, location, "'property' before any 'element'");
      PlyProperty p;
      if (words.size() >= 2 && words[1] == "list") {
        require_input(words.size() == 5, source, location, "'property list' needs two types and a name");
        p.count_size = ply_type_size(words[2]);
        p.count_signed = ply_type_signed(words[2]);
        p.size = ply_type_size(words[3]);
        require_input(
            p.count_size > 0 && p.count_size <= 4 && p.size > 0, source, location,
            "unknown or unsupported list types '" + std::string(words[2]) + " " + std::string(words[3]) + "'");
        // Assimp reads a float length as a float and rounds it (found by fuzz/mesh_ply: its triangulation aborts).
        require_input(!ply_type_float(words[2]), source, location,
                      "the list length type '" + std::string(words[2]) + "' is not an integer type");
        p.face_indices = elements.back().name == "face" && (words[4] == "vertex_indices" || words[4] == "vertex_index");
      } else {
        require_input(words.size() == 3, source, location, "'property' needs a type and a name");
        p.size = ply_type_size(words[1]);
        require_input(p.size > 0, source, location, "unknown property type '" + std::string(words[1]) + "'");
      }
      elements.back().properties.push_back(p);
    } else if (words[0] == "end_header") {
      header_ended = true;
      break;
    } else if (!(words[0] == "comment" || words[0] == "obj_info" || (words[0] == "ply" && line_number == 1))) {
      // Assimp ends an element's property list at a line it does not know, so the layouts would differ
      // (found by fuzz/mesh_ply: it then sized a list from vertex bytes and allocated 34 GB).
      throw InputError(source, location, "unknown header line '" + std::string(words[0].substr(0, 40)) + "'");
    }
  }
  // "end_header" glued to what follows ("end_header0 0 0") makes Assimp's parser loop forever (found by
  // fuzz/mesh_ply).
  require_input(header_ended, source, "header", "no line 'end_header' ends the header");
  require_input(format != Format::unknown, source, "header", "no 'format' line");
  for (const PlyElement& e : elements) {
    require_input(e.count == 0 || !e.properties.empty(), source, "line " + std::to_string(e.header_line),
                  "element '" + e.name + "' declares " + std::to_string(e.count) + " items but no properties");
    // Assimp reads the count of an element whose name it does not know as 0 and so takes the next element's data
    // from that element's bytes (found by fuzz/mesh_ply: a face list length read from vertex bytes asked for
    // 13.5 GB).
    require_input(e.count == 0 || is_assimp_ply_element(e.name), source, "line " + std::to_string(e.header_line),
                  "element '" + e.name.substr(0, 40) + "' with " + std::to_string(e.count) +
                      " items is not one the PLY reader knows (vertex, face, tristrips, edge, material)");
  }

  const std::uint64_t body_size = bytes.size() - body;
  if (format == Format::ascii) {
    require_no_lone_carriage_return(body, bytes.size());
    // Each value takes at least one character and one separator; lists are walked token by token. Each item is
    // one line, as Assimp reads it: a short line would make it parse the next line's words as numbers, throw
    // and leak its mesh (found by fuzz/mesh_ply).
    std::size_t cursor = body;
    const auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    const auto next_token = [&](std::string_view& token) {
      while (cursor < bytes.size() && is_blank(bytes[cursor])) ++cursor;
      const std::size_t start = cursor;
      while (cursor < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[cursor]))) ++cursor;
      token = std::string_view(bytes.data() + start, cursor - start);
      return !token.empty();
    };
    const auto value = [&](std::string_view& token, const PlyElement& e, std::uint64_t i) {
      if (!next_token(token)) {
        fail_element(source, cursor, e.name, i,
                     cursor < bytes.size() ? "the line ends before the item does" : "file ends");
      }
      if (!is_ply_number(token))
        fail_element(source, cursor - token.size(), e.name, i, "a value is not a finite number");
    };
    for (const PlyElement& e : elements) {
      const std::uint64_t min_bytes = e.count * std::max<std::size_t>(e.properties.size(), 1);
      require_input(min_bytes <= body_size, source, "line " + std::to_string(e.header_line),
                    "element '" + e.name + "' declares " + std::to_string(e.count) + " items but the file has only " +
                        std::to_string(body_size) + " bytes of data");
      for (std::uint64_t i = 0; i < e.count; ++i) {
        while (cursor < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[cursor]))) ++cursor;
        for (const PlyProperty& p : e.properties) {
          std::string_view token;
          value(token, e, i);
          if (p.count_size == 0) continue;
          std::int64_t n = -1;
          std::from_chars(token.data(), token.data() + token.size(), n);
          const std::uint64_t remaining = bytes.size() - cursor;
          if (n < 0 || static_cast<std::uint64_t>(n) > remaining / 2 + 1) {
            fail_element(source, cursor - token.size(), e.name, i,
                         "list length " + std::to_string(n) + " is negative or longer than the rest of the file");
          }
          if (p.face_indices && n == 0) fail_element(source, cursor - token.size(), e.name, i, face_without_indices);
          for (std::int64_t k = 0; k < n; ++k) value(token, e, i);
        }
        std::string_view extra;
        if (next_token(extra)) fail_element(source, cursor - extra.size(), e.name, i, "the line holds more values");
      }
    }
    return {};
  }

  // Binary: fixed-size elements are skipped in one step, elements with lists item by item.
  const bool big_endian = format == Format::big;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  std::uint64_t cursor = body;
  for (const PlyElement& e : elements) {
    const bool has_list =
        std::any_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.count_size > 0; });
    std::uint64_t min_stride = 0;
    for (const PlyProperty& p : e.properties) min_stride += p.count_size > 0 ? p.count_size : p.size;
    const std::uint64_t remaining = bytes.size() - cursor;
    require_input(min_stride == 0 || e.count <= remaining / min_stride, source, "line " + std::to_string(e.header_line),
                  "element '" + e.name + "' declares " + std::to_string(e.count) + " items of at least " +
                      std::to_string(min_stride) + " bytes but only " + std::to_string(remaining) +
                      " bytes remain in the file");
    if (!has_list) {
      cursor += e.count * min_stride;
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (p.count_size == 0) {
          if (cursor + p.size > bytes.size()) fail_element(source, cursor, e.name, i, "file ends");
          cursor += p.size;
          continue;
        }
        if (cursor + p.count_size > bytes.size()) fail_element(source, cursor, e.name, i, "file ends");
        const std::int64_t n = read_binary_count(data + cursor, p.count_size, p.count_signed, big_endian);
        cursor += p.count_size;
        if (n < 0 || static_cast<std::uint64_t>(n) > (bytes.size() - cursor) / p.size) {
          fail_element(source, cursor - p.count_size, e.name, i,
                       "list length " + std::to_string(n) + " is negative or longer than the rest of the file");
        }
        if (p.face_indices && n == 0) fail_element(source, cursor - p.count_size, e.name, i, face_without_indices);
        cursor += static_cast<std::uint64_t>(n) * p.size;
      }
    }
  }
  // Assimp 5.2.5 skips one line feed after the end_header line even in a binary file, so a body whose first byte
  // is 0x0A would be read one byte off (found by fuzz/mesh_ply); with one more line feed it reads right.
  if (bytes[body] != '\n') return {};
  bytes.insert(body, 1, '\n');
  return bytes;
}

// ---------------------------------------------------------------------------------------------- STL

/// Checks ASCII STL token by token against its grammar: `solid [name]`, then facets of `facet normal n n n`,
/// `outer loop`, three `vertex x y z`, `endloop`, `endfacet`, then `endsolid [name]` (which the last solid may
/// lack); several solids may follow each other. Assimp leaks its mesh when it stops halfway (a value that is not a
/// number, a facet cut short; found by fuzz/mesh_stl), so whatever would stop it is rejected here first.
void check_ascii_stl(const std::string& bytes, const std::string& source) {
  std::size_t cursor = 0;
  std::size_t line = 1;
  const auto skip_space = [&] {
    while (cursor < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[cursor]))) {
      if (bytes[cursor] == '\n') ++line;
      ++cursor;
    }
  };
  const auto next_token = [&] {
    skip_space();
    const std::size_t start = cursor;
    while (cursor < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[cursor]))) ++cursor;
    return std::string_view(bytes.data() + start, cursor - start);
  };
  const auto skip_line = [&] {
    while (cursor < bytes.size() && bytes[cursor] != '\n') ++cursor;
  };
  const auto fail = [&](const std::string& problem) {
    throw InputError(source, "line " + std::to_string(line), problem);
  };
  const auto expect = [&](std::string_view word) {
    const std::string_view token = next_token();
    if (token != word) {
      fail("expected '" + std::string(word) + "', found " +
           (token.empty() ? std::string("the end of the file") : "'" + std::string(token.substr(0, 40)) + "'"));
    }
  };
  // Assimp reads a facet's "normal" and the numbers after "normal" and "vertex" on the keyword's line.
  const auto word_on_line = [&] {
    while (cursor < bytes.size() && (bytes[cursor] == ' ' || bytes[cursor] == '\t')) ++cursor;
    const std::size_t start = cursor;
    while (cursor < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[cursor]))) ++cursor;
    return std::string_view(bytes.data() + start, cursor - start);
  };
  const auto expect_numbers = [&](const char* what) {
    for (int k = 0; k < 3; ++k) {
      const std::string_view token = word_on_line();
      if (token.empty()) fail(std::string(what) + " needs three numbers on its line");
      if (!is_ply_number(token)) {
        fail(std::string(what) + " value '" + std::string(token.substr(0, 40)) + "' is not a finite number");
      }
    }
  };
  const auto control = std::find_if(bytes.begin(), bytes.end(), is_control_byte);
  if (control != bytes.end()) {
    cursor = static_cast<std::size_t>(control - bytes.begin());
    throw InputError(source, "byte " + std::to_string(cursor), "a control byte in ASCII STL");
  }
  for (std::string_view token = next_token(); !token.empty(); token = next_token()) {
    if (token != "solid") fail("expected 'solid', found '" + std::string(token.substr(0, 40)) + "'");
    // The name: Assimp takes the line's first word (at most 1023 bytes) and reads the words after it as
    // keywords or skips them, so no keyword may follow on that line.
    for (bool first = true;; first = false) {
      const std::string_view word = word_on_line();
      if (word.empty()) break;
      if (first && word.size() >= 1024) fail("the solid's name is longer than 1023 bytes");
      if (word == "facet" || word == "vertex" || word.starts_with("endsolid")) {
        fail("'" + std::string(word.substr(0, 40)) + "' on the line of 'solid'");
      }
    }
    while (true) {
      token = next_token();
      if (token == "endsolid") break;
      if (token.empty()) return;  // no endsolid after the last facet: Assimp only warns
      if (token != "facet") {
        fail("expected 'facet' or 'endsolid', found '" + std::string(token.substr(0, 40)) + "'");
      }
      if (word_on_line() != "normal") fail("'facet' without 'normal' after it on its line");
      expect_numbers("facet normal");
      expect("outer");
      expect("loop");
      for (int v = 0; v < 3; ++v) {
        expect("vertex");
        expect_numbers("vertex");
      }
      expect("endloop");
      expect("endfacet");
    }
    skip_line();  // the name after endsolid
  }
}

void check_stl(const std::filesystem::path& path, std::uintmax_t size) {
  const std::string source = path.string();
  const std::string head = read_prefix(path, 1024);
  if (size >= 84) {
    std::uint32_t count = 0;
    for (int b = 0; b < 4; ++b)
      count |= static_cast<std::uint32_t>(static_cast<unsigned char>(head[80 + b])) << (8 * b);
    if (84 + 50 * static_cast<std::uint64_t>(count) == size) return;  // consistent binary STL
  }
  // Otherwise it must be ASCII STL: "solid" followed by text with "facet" (binary headers may start with
  // "solid" too, so look for a facet keyword and for the absence of control bytes).
  const bool starts_solid = head.compare(0, 5, "solid") == 0;
  const bool textual = std::none_of(head.begin(), head.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 9 || (u > 13 && u < 32);
  });
  if (starts_solid && textual &&
      (head.find("facet") != std::string::npos || head.find("endsolid") != std::string::npos)) {
    check_ascii_stl(read_file(path), source);
    return;
  }
  if (size < 84) throw InputError(source, "byte 0", "too short for a binary STL (" + std::to_string(size) + " bytes)");
  std::uint32_t count = 0;
  for (int b = 0; b < 4; ++b) count |= static_cast<std::uint32_t>(static_cast<unsigned char>(head[80 + b])) << (8 * b);
  throw InputError(source, "byte 80",
                   "binary STL declares " + std::to_string(count) + " triangles (" +
                       std::to_string(84 + 50 * static_cast<std::uint64_t>(count)) + " bytes) but the file has " +
                       std::to_string(size) + " bytes");
}

// ---------------------------------------------------------------------------------------------- OBJ

void check_obj(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string bytes = read_file(path);
  // First pass: totals, so faces may refer to vertices defined later (rare but legal).
  std::uint64_t total[3] = {0, 0, 0};  // v, vt, vn
  const auto for_each_line = [&](auto&& visit) {
    std::size_t pos = 0, line_number = 0;
    while (pos < bytes.size()) {
      std::size_t eol = bytes.find('\n', pos);
      if (eol == std::string::npos) eol = bytes.size();
      ++line_number;
      std::string_view line(bytes.data() + pos, eol - pos);
      pos = eol + 1;
      std::size_t start = 0;
      while (start < line.size() && (line[start] == ' ' || line[start] == '\t')) ++start;
      line.remove_prefix(start);
      if (line.size() < 2) continue;
      visit(line, line_number);
    }
  };
  for_each_line([&](std::string_view line, std::size_t) {
    if (line[0] != 'v') return;
    if (line[1] == ' ' || line[1] == '\t')
      ++total[0];
    else if (line[1] == 't')
      ++total[1];
    else if (line[1] == 'n')
      ++total[2];
  });
  for (std::uint64_t t : total) {
    require_input(t <= max_elements, source, "", "more than 2^31 - 1 vertices, texture coordinates or normals");
  }
  std::uint64_t seen[3] = {0, 0, 0};
  const char* names[3] = {"vertex", "texture coordinate", "normal"};
  for_each_line([&](std::string_view line, std::size_t line_number) {
    const auto location = [&] { return "line " + std::to_string(line_number); };
    if (line[0] == 'v' && (line[1] == ' ' || line[1] == '\t' || line[1] == 't' || line[1] == 'n')) {
      const int kind = (line[1] == 't') ? 1 : (line[1] == 'n') ? 2 : 0;
      ++seen[kind];
      const auto words = split_words(line);
      for (std::size_t w = 1; w < words.size() && w <= 3; ++w) {
        if (words[w][0] == '#') break;
        double value = 0.0;
        const auto [ptr, ec] = std::from_chars(words[w].data(), words[w].data() + words[w].size(), value);
        if (ec != std::errc() || !std::isfinite(value)) {
          throw InputError(source, location(),
                           std::string(names[kind]) + " coordinate '" + std::string(words[w].substr(0, 32)) +
                               (ec == std::errc::invalid_argument ? "' is not a number" : "' is not a finite number"));
        }
      }
      return;
    }
    if (line[0] != 'f' || (line[1] != ' ' && line[1] != '\t')) return;
    const auto words = split_words(line);
    for (std::size_t w = 1; w < words.size(); ++w) {
      std::string_view corner = words[w];
      if (corner[0] == '#') break;
      for (int kind = 0; kind < 3 && !corner.empty(); ++kind) {
        const std::size_t slash = corner.find('/');
        const std::string_view field = corner.substr(0, slash);
        corner = (slash == std::string_view::npos) ? std::string_view() : corner.substr(slash + 1);
        if (field.empty()) continue;  // "1//3"
        std::int64_t index = 0;
        const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), index);
        if (ec != std::errc() || ptr != field.data() + field.size()) {
          throw InputError(
              source, location(),
              std::string(names[kind]) + " index '" + std::string(field.substr(0, 32)) + "' is not an integer");
        }
        const bool valid = (index > 0 && static_cast<std::uint64_t>(index) <= total[kind]) ||
                           (index < 0 && static_cast<std::uint64_t>(-index) <= seen[kind]);
        if (!valid) {
          throw InputError(source, location(),
                           std::string(names[kind]) + " index " + std::to_string(index) + " is out of range (" +
                               std::to_string(total[kind]) + " defined)");
        }
      }
    }
  });
}

// ---------------------------------------------------------------------------------------------- glTF

std::uint32_t read_u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int b = 0; b < 4; ++b) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + b])) << (8 * b);
  return v;
}

int gltf_component_size(int type) {
  switch (type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

int gltf_component_count(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

std::uint64_t json_uint(const nlohmann::json& object, const char* key, std::uint64_t fallback,
                        const std::string& source, const std::string& location) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  require_input(it->is_number_unsigned() || (it->is_number_integer() && it->get<std::int64_t>() >= 0), source, location,
                std::string("'") + key + "' is not a non-negative integer");
  return it->get<std::uint64_t>();
}

/// Checks buffers, buffer views and accessors of a glTF JSON document against the bytes really present.
/// `bin_size` is the GLB BIN chunk length (buffer 0 without uri), or -1 for .gltf files.
void check_gltf_json(const std::filesystem::path& path, std::string_view json_text, std::int64_t bin_size) {
  const std::string source = path.string();
  const nlohmann::json doc = nlohmann::json::parse(json_text.begin(), json_text.end(), nullptr, false);
  require_input(!doc.is_discarded() && doc.is_object(), source, "JSON", "the glTF JSON does not parse as an object");
  std::vector<std::uint64_t> buffer_sizes;
  if (const auto it = doc.find("buffers"); it != doc.end() && it->is_array()) {
    for (std::size_t b = 0; b < it->size(); ++b) {
      const nlohmann::json& buffer = (*it)[b];
      const std::string location = "buffers[" + std::to_string(b) + "]";
      require_input(buffer.is_object(), source, location, "is not an object");
      const std::uint64_t declared = json_uint(buffer, "byteLength", 0, source, location);
      std::uint64_t available = 0;
      const auto uri = buffer.find("uri");
      if (uri == buffer.end()) {
        require_input(bin_size >= 0, source, location, "has no uri and there is no GLB binary chunk");
        available = static_cast<std::uint64_t>(bin_size);
      } else if (uri->is_string()) {
        const std::string u = uri->get<std::string>();
        if (u.rfind("data:", 0) == 0) {
          const std::size_t comma = u.find(',');
          available = comma == std::string::npos ? 0 : (u.size() - comma - 1) / 4 * 3 + 3;
        } else {
          std::error_code ec;
          const auto file = path.parent_path() / u;
          const auto size = std::filesystem::file_size(file, ec);
          require_input(!ec, source, location, "buffer file '" + u + "' cannot be read");
          available = size;
        }
      }
      require_input(
          declared <= available, source, location,
          "byteLength " + std::to_string(declared) + " exceeds the " + std::to_string(available) + " bytes available");
      buffer_sizes.push_back(declared);
    }
  }
  // Node hierarchy: a forest of bounded depth (readers walk it recursively; a cycle or a chain of a million
  // nodes would overflow their stack).
  if (const auto it = doc.find("nodes"); it != doc.end() && it->is_array()) {
    constexpr std::size_t max_depth = 1024;
    const std::size_t count = it->size();
    std::vector<std::int64_t> parent(count, -1);
    for (std::size_t n = 0; n < count; ++n) {
      const nlohmann::json& node = (*it)[n];
      const std::string location = "nodes[" + std::to_string(n) + "]";
      require_input(node.is_object(), source, location, "is not an object");
      const auto children = node.find("children");
      if (children == node.end()) continue;
      require_input(children->is_array(), source, location, "'children' is not an array");
      for (const nlohmann::json& child : *children) {
        require_input(child.is_number_unsigned() && child.get<std::uint64_t>() < count, source, location,
                      "child index is not a valid node index");
        const auto c = child.get<std::size_t>();
        require_input(c != n && parent[c] < 0, source, location,
                      "node " + std::to_string(c) + " has two parents or is its own child");
        parent[c] = static_cast<std::int64_t>(n);
      }
    }
    for (std::size_t n = 0; n < count; ++n) {
      std::size_t depth = 0;
      for (std::int64_t p = parent[n]; p >= 0; p = parent[static_cast<std::size_t>(p)]) {
        require_input(++depth <= max_depth, source, "nodes[" + std::to_string(n) + "]",
                      "node hierarchy is cyclic or deeper than " + std::to_string(max_depth) + " levels");
      }
    }
  }
  std::vector<std::uint64_t> view_sizes, view_strides;
  if (const auto it = doc.find("bufferViews"); it != doc.end() && it->is_array()) {
    for (std::size_t v = 0; v < it->size(); ++v) {
      const nlohmann::json& view = (*it)[v];
      const std::string location = "bufferViews[" + std::to_string(v) + "]";
      require_input(view.is_object(), source, location, "is not an object");
      const std::uint64_t buffer = json_uint(view, "buffer", buffer_sizes.size(), source, location);
      const std::uint64_t offset = json_uint(view, "byteOffset", 0, source, location);
      const std::uint64_t length = json_uint(view, "byteLength", 0, source, location);
      require_input(buffer < buffer_sizes.size(), source, location, "refers to a missing buffer");
      require_input(offset <= buffer_sizes[buffer] && length <= buffer_sizes[buffer] - offset, source, location,
                    "extends past the end of its buffer");
      view_sizes.push_back(length);
      view_strides.push_back(json_uint(view, "byteStride", 0, source, location));
    }
  }
  if (const auto it = doc.find("accessors"); it != doc.end() && it->is_array()) {
    for (std::size_t a = 0; a < it->size(); ++a) {
      const nlohmann::json& accessor = (*it)[a];
      const std::string location = "accessors[" + std::to_string(a) + "]";
      require_input(accessor.is_object(), source, location, "is not an object");
      const std::uint64_t count = json_uint(accessor, "count", 0, source, location);
      require_input(count <= max_elements, source, location, "count " + std::to_string(count) + " is absurd");
      const auto type = accessor.find("type");
      const auto component = accessor.find("componentType");
      require_input(
          type != accessor.end() && type->is_string() && component != accessor.end() && component->is_number_integer(),
          source, location, "has no valid 'type' or 'componentType'");
      const int element_size =
          gltf_component_count(type->get<std::string>()) * gltf_component_size(component->get<int>());
      require_input(element_size > 0, source, location, "has an unknown type or component type");
      // Accessors without a view are all zeros (plus sparse values) that the reader allocates; bound them by
      // the data really present, generously (a zero morph target of a large mesh is legitimate).
      const std::uint64_t total_bytes = std::accumulate(view_sizes.begin(), view_sizes.end(), std::uint64_t{0});
      require_input(count * static_cast<std::uint64_t>(element_size) <= 64 * total_bytes + (std::uint64_t{1} << 20),
                    source, location,
                    "count " + std::to_string(count) + " is far larger than the file's data could describe");
      if (const auto sparse = accessor.find("sparse"); sparse != accessor.end()) {
        require_input(sparse->is_object(), source, location + ".sparse", "is not an object");
        const std::uint64_t sparse_count = json_uint(*sparse, "count", 0, source, location + ".sparse");
        require_input(sparse_count <= count, source, location + ".sparse", "count exceeds the accessor's count");
        for (const char* part : {"indices", "values"}) {
          const auto it_part = sparse->find(part);
          require_input(it_part != sparse->end() && it_part->is_object(), source, location + ".sparse",
                        std::string("has no '") + part + "'");
          const std::uint64_t part_view = json_uint(*it_part, "bufferView", view_sizes.size(), source, location);
          const std::uint64_t part_offset = json_uint(*it_part, "byteOffset", 0, source, location);
          require_input(part_view < view_sizes.size(), source, location + ".sparse." + part,
                        "refers to a missing buffer view");
          std::uint64_t part_size = static_cast<std::uint64_t>(element_size);
          if (std::string_view(part) == "indices") {
            const auto type_it = it_part->find("componentType");
            require_input(type_it != it_part->end() && type_it->is_number_integer(), source,
                          location + ".sparse.indices", "has no componentType");
            part_size = static_cast<std::uint64_t>(gltf_component_size(type_it->get<int>()));
            require_input(part_size > 0, source, location + ".sparse.indices", "has an unknown componentType");
          }
          require_input(
              part_offset <= view_sizes[part_view] && sparse_count * part_size <= view_sizes[part_view] - part_offset,
              source, location + ".sparse." + part, "extends past the end of its buffer view");
        }
      }
      if (accessor.find("bufferView") == accessor.end()) continue;
      const std::uint64_t view = json_uint(accessor, "bufferView", 0, source, location);
      const std::uint64_t offset = json_uint(accessor, "byteOffset", 0, source, location);
      require_input(view < view_sizes.size(), source, location, "refers to a missing buffer view");
      const std::uint64_t stride =
          std::max<std::uint64_t>(view_strides[view], static_cast<std::uint64_t>(element_size));
      const std::uint64_t needed =
          count == 0 ? 0 : offset + (count - 1) * stride + static_cast<std::uint64_t>(element_size);
      require_input(needed <= view_sizes[view], source, location,
                    std::to_string(count) + " elements need " + std::to_string(needed) + " bytes but its view has " +
                        std::to_string(view_sizes[view]));
    }
  }
}

void check_glb(const std::filesystem::path& path, std::uintmax_t size) {
  const std::string source = path.string();
  require_input(size >= 20, source, "byte 0", "too short for a GLB file (" + std::to_string(size) + " bytes)");
  require_input(size <= (std::uintmax_t{1} << 32), source, "", "larger than GLB's 4 GiB limit");
  const std::string bytes = read_file(path);
  require_input(bytes.compare(0, 4, "glTF") == 0, source, "byte 0", "not a GLB file (no 'glTF' magic)");
  require_input(read_u32(bytes, 4) == 2, source, "byte 4",
                "GLB version " + std::to_string(read_u32(bytes, 4)) + " is not 2");
  const std::uint64_t length = read_u32(bytes, 8);
  require_input(length <= bytes.size(), source, "byte 8",
                "header length " + std::to_string(length) + " exceeds the file size " + std::to_string(bytes.size()));
  const std::uint64_t json_length = read_u32(bytes, 12);
  require_input(read_u32(bytes, 16) == 0x4E4F534Au, source, "byte 16", "first chunk is not JSON");
  require_input(json_length <= length - 20, source, "byte 12",
                "JSON chunk length " + std::to_string(json_length) + " exceeds the file");
  std::int64_t bin_size = -1;
  std::uint64_t next = 20 + json_length;
  if (next + 8 <= length) {
    const std::uint64_t bin_length = read_u32(bytes, next);
    const std::uint32_t type = read_u32(bytes, next + 4);
    require_input(bin_length <= length - next - 8, source, "byte " + std::to_string(next),
                  "chunk length " + std::to_string(bin_length) + " exceeds the file");
    if (type == 0x004E4942u) bin_size = static_cast<std::int64_t>(bin_length);
  } else {
    require_input(next == length, source, "byte " + std::to_string(next), "truncated chunk header");
  }
  check_gltf_json(path, std::string_view(bytes.data() + 20, json_length), bin_size);
}

}  // namespace

std::string check_mesh_file(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw IoError(source, "not a readable file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(source, "cannot determine the file size: " + ec.message());
  require_input(size > 0, source, "", "the file is empty");
  const std::string ext = lower_extension(path);
  if (ext == ".ply") return check_ply(path);
  if (ext == ".stl") {
    check_stl(path, size);
  } else if (ext == ".obj") {
    check_obj(path);
  } else if (ext == ".glb") {
    check_glb(path, size);
  } else if (ext == ".gltf") {
    const std::string text = read_file(path, std::size_t{1} << 30);
    check_gltf_json(path, text, -1);
  }
  return {};
}

}  // namespace forensim
