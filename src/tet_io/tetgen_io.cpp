#include "tet_io/tetgen_io.hpp"

#include <cmath>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "tet_io/number_text.hpp"
#include "tet_io/text_cursor.hpp"

namespace forensim {
namespace {

constexpr std::string_view names_comment = "# forensim attributes:";

/// Line-oriented reader of a TetGen file: skips blank lines and '#' comments, remembers the attribute
/// names comment written by write_tetgen.
class TetgenLines {
 public:
  TetgenLines(std::string_view bytes, std::string source) : m_in(bytes, std::move(source)) {}

  const std::string& source() const { return m_in.source(); }
  std::size_t remaining() const { return m_in.remaining(); }
  std::string location() const { return "line " + std::to_string(m_line); }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(source(), location(), problem); }

  /// Tokens of the next line holding data; empty at the end of the file.
  const std::vector<std::string_view>& next() {
    m_tokens.clear();
    while (!m_in.at_end()) {
      std::string_view text = m_in.line();
      ++m_line;
      if (text.substr(0, names_comment.size()) == names_comment) {
        m_names.clear();
        TextCursor names(text.substr(names_comment.size()), source());
        while (!names.at_line_end()) m_names.emplace_back(names.token_on_line());
      }
      text = text.substr(0, text.find('#'));
      TextCursor words(text, source());
      while (!words.at_line_end()) m_tokens.push_back(words.token_on_line());
      if (!m_tokens.empty()) break;
    }
    return m_tokens;
  }

  std::int64_t integer(std::string_view token, const char* what, std::int64_t min, std::int64_t max) const {
    std::int64_t value = 0;
    if (!parse_integer(token, value)) fail(std::string(what) + " is not an integer");
    if (value < min || value > max) {
      fail(std::string(what) + " " + std::to_string(value) + " is out of range [" + std::to_string(min) + ", " +
           std::to_string(max) + "]");
    }
    return value;
  }

  double finite(std::string_view token, const char* what) const {
    double value = 0.0;
    if (!parse_double(token, value) || !std::isfinite(value)) fail(std::string(what) + " is not a finite number");
    return value;
  }

  /// Attribute names from the names comment, when it has exactly `count` of them.
  std::optional<std::vector<std::string>> names(std::size_t count) const {
    if (m_names.size() != count) return std::nullopt;
    return m_names;
  }

 private:
  TextCursor m_in;
  std::size_t m_line = 0;
  std::vector<std::string_view> m_tokens;
  std::vector<std::string> m_names;
};

/// Stores attribute columns as fields: consecutive "<n>.x", "<n>.y", "<n>.z" become one vector field.
void store_attributes(FieldSet& fields, const std::vector<std::string>& names,
                      std::vector<std::vector<double>>& columns) {
  for (std::size_t a = 0; a < names.size(); ++a) {
    const std::string& name = names[a];
    if (a + 2 < names.size() && name.size() > 2 && name.compare(name.size() - 2, 2, ".x") == 0) {
      const std::string base = name.substr(0, name.size() - 2);
      if (names[a + 1] == base + ".y" && names[a + 2] == base + ".z") {
        std::vector<Vec3> vectors(columns[a].size());
        for (std::size_t i = 0; i < vectors.size(); ++i) {
          vectors[i] = Vec3(columns[a][i], columns[a + 1][i], columns[a + 2][i]);
        }
        fields.vectors[base] = std::move(vectors);
        a += 2;
        continue;
      }
    }
    fields.scalars[name] = std::move(columns[a]);
  }
}

std::vector<std::string> default_names(const char* prefix, std::size_t count) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) names.push_back(prefix + std::to_string(i));
  return names;
}

/// Reads the .node file; returns the first index (0 or 1).
std::int64_t read_node_file(std::string_view bytes, const std::string& source, TetMesh& mesh) {
  TetgenLines in(bytes, source);
  const auto& header = in.next();
  if (header.empty()) in.fail("empty .node file");
  if (header.size() < 2) in.fail(".node header needs at least '<#nodes> <dimension>'");
  const std::int64_t count = in.integer(header[0], "node count", 0, INT32_MAX);
  in.integer(header[1], "dimension", 3, 3);  // volume meshes only
  const std::int64_t attribute_count = header.size() > 2 ? in.integer(header[2], "attribute count", 0, 1000) : 0;
  const std::int64_t markers = header.size() > 3 ? in.integer(header[3], "boundary marker flag", 0, 1) : 0;
  const std::size_t columns = 4 + static_cast<std::size_t>(attribute_count + markers);
  // Every value takes at least 2 bytes ("0 "), so the declared table must fit in what is left.
  if (static_cast<std::uint64_t>(count) > in.remaining() / (2 * columns)) {
    in.fail("node count " + std::to_string(count) + " with " + std::to_string(columns) +
            " values each cannot fit in the remaining " + std::to_string(in.remaining()) + " bytes");
  }
  const auto names = in.names(static_cast<std::size_t>(attribute_count));
  mesh.positions.reserve(static_cast<std::size_t>(count));
  std::vector<std::vector<double>> attributes(static_cast<std::size_t>(attribute_count));
  for (auto& a : attributes) a.reserve(static_cast<std::size_t>(count));
  std::vector<double> marker_values;
  std::int64_t first = 0;
  for (std::int64_t i = 0; i < count; ++i) {
    const auto& tokens = in.next();
    if (tokens.empty()) in.fail("file ends after " + std::to_string(i) + " of " + std::to_string(count) + " nodes");
    if (tokens.size() != columns) {
      in.fail("node line has " + std::to_string(tokens.size()) + " values, expected " + std::to_string(columns));
    }
    const std::int64_t index = in.integer(tokens[0], "node index", 0, INT64_MAX - INT32_MAX);
    if (i == 0) {
      if (index > 1) in.fail("first node index is " + std::to_string(index) + " (must be 0 or 1)");
      first = index;
    } else if (index != first + i) {
      in.fail("node index " + std::to_string(index) + " is out of sequence (expected " + std::to_string(first + i) +
              ")");
    }
    mesh.positions.emplace_back(in.finite(tokens[1], "x"), in.finite(tokens[2], "y"), in.finite(tokens[3], "z"));
    for (std::size_t a = 0; a < attributes.size(); ++a) attributes[a].push_back(in.finite(tokens[4 + a], "attribute"));
    if (markers)
      marker_values.push_back(static_cast<double>(in.integer(tokens.back(), "boundary marker", INT32_MIN, INT32_MAX)));
  }
  store_attributes(mesh.vertex_fields, names ? *names : default_names("attribute_", attributes.size()), attributes);
  if (markers) mesh.vertex_fields.scalars["boundary_marker"] = std::move(marker_values);
  return first;
}

void read_ele_file(std::string_view bytes, const std::string& source, std::int64_t first, TetMesh& mesh) {
  TetgenLines in(bytes, source);
  const auto& header = in.next();
  if (header.empty()) in.fail("empty .ele file");
  if (header.size() < 2) in.fail(".ele header needs at least '<#tets> <nodes per tet>'");
  const std::int64_t count = in.integer(header[0], "tet count", 0, INT32_MAX);
  const std::int64_t corners = in.integer(header[1], "nodes per tet", 4, 10);
  if (corners != 4 && corners != 10) in.fail("nodes per tet must be 4 or 10, not " + std::to_string(corners));
  const std::int64_t attribute_count = header.size() > 2 ? in.integer(header[2], "attribute count", 0, 1000) : 0;
  const std::size_t columns = 1 + static_cast<std::size_t>(corners + attribute_count);
  if (static_cast<std::uint64_t>(count) > in.remaining() / (2 * columns)) {
    in.fail("tet count " + std::to_string(count) + " with " + std::to_string(columns) +
            " values each cannot fit in the remaining " + std::to_string(in.remaining()) + " bytes");
  }
  const auto names = attribute_count > 1 ? in.names(static_cast<std::size_t>(attribute_count - 1)) : std::nullopt;
  const std::int64_t node_count = static_cast<std::int64_t>(mesh.positions.size());
  mesh.tets.reserve(static_cast<std::size_t>(count));
  if (attribute_count > 0) mesh.tet_labels.reserve(static_cast<std::size_t>(count));
  std::vector<std::vector<double>> attributes(static_cast<std::size_t>(std::max<std::int64_t>(attribute_count - 1, 0)));
  std::int64_t first_tet = 0;
  for (std::int64_t t = 0; t < count; ++t) {
    const auto& tokens = in.next();
    if (tokens.empty()) in.fail("file ends after " + std::to_string(t) + " of " + std::to_string(count) + " tets");
    if (tokens.size() != columns) {
      in.fail("tet line has " + std::to_string(tokens.size()) + " values, expected " + std::to_string(columns));
    }
    const std::int64_t index = in.integer(tokens[0], "tet index", 0, INT64_MAX - INT32_MAX);
    if (t == 0) first_tet = index;
    if (index != first_tet + t) in.fail("tet index " + std::to_string(index) + " is out of sequence");
    Tet tet;
    for (int k = 0; k < 4; ++k) {
      const std::int64_t node = in.integer(tokens[1 + k], "node index", INT64_MIN, INT64_MAX);
      if (node < first || node - first >= node_count) {
        in.fail("node index " + std::to_string(node) + " is out of range [" + std::to_string(first) + ", " +
                std::to_string(first + node_count - 1) + "]");
      }
      tet[k] = static_cast<Index>(node - first);
    }
    mesh.tets.push_back(tet);
    if (attribute_count > 0) {
      const double region = in.finite(tokens[1 + static_cast<std::size_t>(corners)], "region attribute");
      if (region != std::floor(region) || std::abs(region) > INT32_MAX) {
        in.fail("region attribute " + std::string(tokens[1 + static_cast<std::size_t>(corners)]) +
                " is not an integer label");
      }
      mesh.tet_labels.push_back(static_cast<int>(region));
      for (std::size_t a = 0; a < attributes.size(); ++a) {
        attributes[a].push_back(in.finite(tokens[2 + static_cast<std::size_t>(corners) + a], "tet attribute"));
      }
    }
  }
  store_attributes(mesh.tet_fields, names ? *names : default_names("tet_attribute_", attributes.size()), attributes);
}

/// Attribute columns of a field set, in name order: scalars, then vectors as three columns.
struct Columns {
  std::vector<std::string> names;
  std::vector<const std::vector<double>*> scalars;
  std::vector<std::pair<const std::vector<Vec3>*, int>> vector_parts;  // in order after the scalars
};

Columns columns_of(const FieldSet& fields, const std::string& skip) {
  Columns c;
  for (const auto& [name, values] : fields.scalars) {
    if (name == skip) continue;
    c.names.push_back(name);
    c.scalars.push_back(&values);
  }
  for (const auto& [name, values] : fields.vectors) {
    for (int k = 0; k < 3; ++k) {
      c.names.push_back(name + (k == 0 ? ".x" : k == 1 ? ".y" : ".z"));
      c.vector_parts.emplace_back(&values, k);
    }
  }
  return c;
}

void append_columns(std::string& out, const Columns& c, std::size_t i) {
  for (const auto* s : c.scalars) {
    out += ' ';
    append_double(out, (*s)[i]);
  }
  for (const auto& [v, k] : c.vector_parts) {
    out += ' ';
    append_double(out, (*v)[i][k]);
  }
}

void append_names_comment(std::string& out, const Columns& c) {
  if (c.names.empty()) return;
  out += names_comment;
  for (const std::string& name : c.names) {
    out += ' ';
    // Names with blanks or '#' would not survive the comment: fall back to a neutral spelling.
    for (char ch : name) out += (ch == ' ' || ch == '\t' || ch == '#' || ch == '\n' || ch == '\r') ? '_' : ch;
  }
  out += '\n';
}

std::filesystem::path with_extension(const std::filesystem::path& base, const char* extension) {
  return std::filesystem::path(base.string() + extension);
}

}  // namespace

TetMesh read_tetgen(const std::filesystem::path& node_or_ele_or_basename) {
  std::filesystem::path base = node_or_ele_or_basename;
  if (base.extension() == ".node" || base.extension() == ".ele") base.replace_extension();
  const std::filesystem::path node_path = with_extension(base, ".node");
  const std::filesystem::path ele_path = with_extension(base, ".ele");
  const std::string node_bytes = read_file(node_path);
  const std::string ele_bytes = read_file(ele_path);
  return parse_tetgen(node_bytes, ele_bytes, node_path.string(), ele_path.string());
}

TetMesh parse_tetgen(std::string_view node_bytes, std::string_view ele_bytes, const std::string& node_source,
                     const std::string& ele_source) {
  TetMesh mesh;
  const std::int64_t first = read_node_file(node_bytes, node_source, mesh);
  read_ele_file(ele_bytes, ele_source, first, mesh);
  bool labelled = false;
  for (int label : mesh.tet_labels) labelled = labelled || label != tissue_flesh;
  if (!labelled) mesh.tet_labels.clear();
  mesh.validate(ele_source);
  return mesh;
}

void write_tetgen(const std::filesystem::path& basename_or_file, const TetMesh& mesh) {
  std::filesystem::path basename = basename_or_file;
  if (basename.extension() == ".node" || basename.extension() == ".ele") basename.replace_extension();
  mesh.validate("mesh written to " + basename.string());
  const auto marker_it = mesh.vertex_fields.scalars.find("boundary_marker");
  bool markers = marker_it != mesh.vertex_fields.scalars.end();
  if (markers) {
    for (double m : marker_it->second) markers = markers && m == std::floor(m) && std::abs(m) <= INT32_MAX;
  }
  const Columns node_columns = columns_of(mesh.vertex_fields, markers ? "boundary_marker" : "");
  const Columns tet_columns = columns_of(mesh.tet_fields, "");

  std::string node;
  node.reserve(64 + mesh.vertex_count() * (64 + 20 * node_columns.names.size()));
  node += "# forensim tet mesh: " + std::to_string(mesh.vertex_count()) + " nodes, 1-based\n";
  append_names_comment(node, node_columns);
  node += std::to_string(mesh.vertex_count()) + " 3 " + std::to_string(node_columns.names.size()) +
          (markers ? " 1\n" : " 0\n");
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    append_integer(node, static_cast<std::int64_t>(v) + 1);
    for (int k = 0; k < 3; ++k) {
      node += ' ';
      append_double(node, mesh.positions[v][k]);
    }
    append_columns(node, node_columns, v);
    if (markers) {
      node += ' ';
      append_integer(node, static_cast<std::int64_t>(marker_it->second[v]));
    }
    node += '\n';
  }

  std::string ele;
  ele.reserve(64 + mesh.tet_count() * (56 + 20 * tet_columns.names.size()));
  ele += "# forensim tet mesh: " + std::to_string(mesh.tet_count()) + " tets, region attribute = tet label\n";
  append_names_comment(ele, tet_columns);
  ele += std::to_string(mesh.tet_count()) + " 4 " + std::to_string(1 + tet_columns.names.size()) + "\n";
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    append_integer(ele, static_cast<std::int64_t>(t) + 1);
    for (Index v : mesh.tets[t]) {
      ele += ' ';
      append_integer(ele, std::int64_t{v} + 1);
    }
    ele += ' ';
    append_integer(ele, mesh.label(t));
    append_columns(ele, tet_columns, t);
    ele += '\n';
  }
  write_file_atomic(with_extension(basename, ".node"), node);
  write_file_atomic(with_extension(basename, ".ele"), ele);
}

}  // namespace forensim
