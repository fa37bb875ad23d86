#include "tet_io/vtu_reader.hpp"

#include <cmath>
#include <cstring>
#include <set>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "tet_io/text_cursor.hpp"
#include "tet_io/vtk_binary_array.hpp"
#include "tet_io/xml_lite.hpp"

namespace forensim {
namespace {

constexpr std::int64_t vtk_tetra = 10;
constexpr std::int64_t vtk_triangle = 5;
/// Deflate's maximum expansion; bounds what a compressed file of a given size can declare.
constexpr std::uint64_t max_zlib_ratio = 1032;

enum class ValueType { int8, uint8, int16, uint16, int32, uint32, int64, uint64, float32, float64 };

struct TypeInfo {
  const char* name;
  ValueType type;
  std::size_t size;
};

constexpr TypeInfo type_table[] = {
    {"Int8", ValueType::int8, 1},       {"UInt8", ValueType::uint8, 1},    {"Int16", ValueType::int16, 2},
    {"UInt16", ValueType::uint16, 2},   {"Int32", ValueType::int32, 4},    {"UInt32", ValueType::uint32, 4},
    {"Int64", ValueType::int64, 8},     {"UInt64", ValueType::uint64, 8},  {"Float32", ValueType::float32, 4},
    {"Float64", ValueType::float64, 8}, {"Char", ValueType::int8, 1},      {"UChar", ValueType::uint8, 1},
    {"Short", ValueType::int16, 2},     {"UShort", ValueType::uint16, 2},  {"Int", ValueType::int32, 4},
    {"UInt", ValueType::uint32, 4},     {"Long", ValueType::int64, 8},     {"ULong", ValueType::uint64, 8},
    {"Float", ValueType::float32, 4},   {"Double", ValueType::float64, 8},
};

bool is_real(ValueType t) {
  return t == ValueType::float32 || t == ValueType::float64;
}

template <class T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

/// Value `i` of a binary array as double (exact for every integer up to 2^53).
double real_at(const std::string& bytes, std::size_t i, const TypeInfo& t) {
  const char* p = bytes.data() + i * t.size;
  switch (t.type) {
    case ValueType::int8:
      return load<std::int8_t>(p);
    case ValueType::uint8:
      return load<std::uint8_t>(p);
    case ValueType::int16:
      return load<std::int16_t>(p);
    case ValueType::uint16:
      return load<std::uint16_t>(p);
    case ValueType::int32:
      return load<std::int32_t>(p);
    case ValueType::uint32:
      return load<std::uint32_t>(p);
    case ValueType::int64:
      return static_cast<double>(load<std::int64_t>(p));
    case ValueType::uint64:
      return static_cast<double>(load<std::uint64_t>(p));
    case ValueType::float32:
      return load<float>(p);
    case ValueType::float64:
      return load<double>(p);
  }
  return 0.0;
}

/// Value `i` of an integer binary array; false when it does not fit an int64.
bool integer_at(const std::string& bytes, std::size_t i, const TypeInfo& t, std::int64_t& value) {
  const char* p = bytes.data() + i * t.size;
  switch (t.type) {
    case ValueType::int8:
      value = load<std::int8_t>(p);
      return true;
    case ValueType::uint8:
      value = load<std::uint8_t>(p);
      return true;
    case ValueType::int16:
      value = load<std::int16_t>(p);
      return true;
    case ValueType::uint16:
      value = load<std::uint16_t>(p);
      return true;
    case ValueType::int32:
      value = load<std::int32_t>(p);
      return true;
    case ValueType::uint32:
      value = load<std::uint32_t>(p);
      return true;
    case ValueType::int64:
      value = load<std::int64_t>(p);
      return true;
    case ValueType::uint64: {
      const auto u = load<std::uint64_t>(p);
      value = static_cast<std::int64_t>(u);
      return u <= static_cast<std::uint64_t>(INT64_MAX);
    }
    default:
      return false;
  }
}

/// What a single-piece grid of one cell kind holds.
struct VtuGrid {
  std::vector<Vec3> positions;
  std::vector<Index> cells;  ///< nodes_per_cell indices per cell
  FieldSet point_fields, cell_fields;
  std::vector<int> labels;
};

/// The one cell kind a reader accepts.
struct CellKind {
  std::int64_t vtk_type;
  int nodes;
  const char* name;  ///< for messages: "tetrahedra (VTK_TETRA = 10)"
};

class VtuReader {
 public:
  VtuReader(std::string_view bytes, std::string source) : m_bytes(bytes), m_source(std::move(source)) {}

  VtuGrid read(const CellKind& kind) {
    m_doc = parse_xml(m_bytes, m_source);
    const XmlElement& root = m_doc.root;
    if (root.name != "VTKFile") fail(root, "root element is <" + root.name + ">, not <VTKFile>");
    const std::string type = attribute(root, "type");
    if (type != "UnstructuredGrid") {
      fail(root, "VTK file type '" + type + "' is not supported; read_vtu reads UnstructuredGrid (.vtu)");
    }
    const std::string* version = root.attribute("version");
    if (version && *version != "0.1" && *version != "1.0" && version->rfind("2.", 0) != 0) {
      fail(root, "VTK XML version '" + *version + "' is not supported (0.1, 1.0, 2.x are)");
    }
    const std::string* byte_order = root.attribute("byte_order");
    if (byte_order && *byte_order != "LittleEndian") {
      fail(root, "byte_order '" + *byte_order + "' is not supported; only LittleEndian is");
    }
    const std::string* header = root.attribute("header_type");
    if (header && *header != "UInt32" && *header != "UInt64") {
      fail(root, "header_type '" + *header + "' is not UInt32 or UInt64");
    }
    m_header = header && *header == "UInt64" ? VtkHeaderType::uint64 : VtkHeaderType::uint32;
    if (const std::string* compressor = root.attribute("compressor")) {
      if (*compressor != "vtkZLibDataCompressor") {
        fail(root, "compressor '" + *compressor + "' is not supported; only vtkZLibDataCompressor is");
      }
      m_compressed = true;
    }
    if (const XmlElement* appended = root.child("AppendedData")) {
      const std::string* encoding = appended->attribute("encoding");
      if (!encoding || (*encoding != "raw" && *encoding != "base64")) {
        fail(*appended, "appended data encoding '" + (encoding ? *encoding : std::string()) +
                            "' is not supported; only raw and base64 are");
      }
      m_appended_base64 = *encoding == "base64";
      if (!m_doc.appended) fail(*appended, "appended data block not found");
    }

    const XmlElement* grid = root.child("UnstructuredGrid");
    if (!grid) fail(root, "no <UnstructuredGrid> element");
    const XmlElement* piece = nullptr;
    for (const XmlElement& c : grid->children) {
      if (c.name != "Piece") continue;
      if (piece) fail(c, "several <Piece> elements; read_vtu reads single-piece files");
      piece = &c;
    }
    if (!piece) fail(*grid, "no <Piece> element");
    const std::size_t points = count(*piece, "NumberOfPoints");
    const std::size_t cells = count(*piece, "NumberOfCells");

    VtuGrid mesh;
    const XmlElement* points_element = piece->child("Points");
    if (!points_element) fail(*piece, "no <Points> element");
    const XmlElement* points_array = points_element->child("DataArray");
    if (!points_array) fail(*points_element, "<Points> has no DataArray");
    const std::vector<double> xyz = reals(*points_array, points, 3);
    mesh.positions.resize(points);
    for (std::size_t v = 0; v < points; ++v) {
      mesh.positions[v] = Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
      if (!mesh.positions[v].allFinite()) fail(*points_array, "point " + std::to_string(v) + " is not finite");
    }

    const XmlElement* cells_element = piece->child("Cells");
    if (!cells_element) {
      if (cells > 0) fail(*piece, "no <Cells> element");
    } else {
      read_cells(*cells_element, cells, points, kind, mesh.cells);
    }
    if (const XmlElement* data = piece->child("PointData")) read_fields(*data, points, mesh.point_fields, nullptr);
    if (const XmlElement* data = piece->child("CellData")) read_fields(*data, cells, mesh.cell_fields, &mesh.labels);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const XmlElement& at, const std::string& problem) const {
    throw InputError(m_source, at.location(), problem);
  }

  std::string attribute(const XmlElement& e, const char* key) const {
    const std::string* value = e.attribute(key);
    if (!value) fail(e, "<" + e.name + "> has no " + key + " attribute");
    return *value;
  }

  std::size_t count(const XmlElement& e, const char* key) const {
    const std::string text = attribute(e, key);
    std::int64_t value = 0;
    if (!parse_integer(text, value) || value < 0 || value > INT32_MAX) {
      fail(e, std::string(key) + " '" + text + "' is not a count in [0, 2^31-1]");
    }
    return static_cast<std::size_t>(value);
  }

  const TypeInfo& type_of(const XmlElement& array) const {
    const std::string name = attribute(array, "type");
    for (const TypeInfo& t : type_table) {
      if (name == t.name) return t;
    }
    fail(array, "unsupported DataArray type '" + name + "'");
  }

  std::size_t components_of(const XmlElement& array) const {
    const std::string* text = array.attribute("NumberOfComponents");
    if (!text) return 1;
    std::int64_t value = 0;
    if (!parse_integer(*text, value) || value < 1 || value > 1024) {
      fail(array, "NumberOfComponents '" + *text + "' is not in [1, 1024]");
    }
    return static_cast<std::size_t>(value);
  }

  /// Raw little-endian bytes of a binary (inline or appended) array of `values` values of `type`.
  std::string binary_bytes(const XmlElement& array, const std::string& format, std::size_t values,
                           const TypeInfo& type) const {
    const std::uint64_t expected = static_cast<std::uint64_t>(values) * type.size;
    // Declared sizes must be possible for this file before anything is allocated.
    const std::uint64_t limit = m_compressed ? m_bytes.size() * max_zlib_ratio + 1024 : m_bytes.size();
    if (expected > limit) {
      fail(array, "array of " + std::to_string(values) + " values cannot fit in a file of " +
                      std::to_string(m_bytes.size()) + " bytes");
    }
    if (format == "binary") {
      return decode_vtk_base64_array(array.text, m_header, m_compressed, static_cast<std::size_t>(expected), m_source,
                                     array.location());
    }
    if (!m_doc.appended) fail(array, "format=\"appended\" but the file has no <AppendedData>");
    const auto [begin, end] = *m_doc.appended;
    const std::string offset_text = attribute(array, "offset");
    std::int64_t offset = 0;
    if (!parse_integer(offset_text, offset) || offset < 0 || static_cast<std::uint64_t>(offset) >= end - begin) {
      fail(array,
           "offset '" + offset_text + "' is outside the appended data (" + std::to_string(end - begin) + " bytes)");
    }
    const std::size_t start = begin + static_cast<std::size_t>(offset);
    if (m_appended_base64) {
      return decode_vtk_appended_base64(m_bytes.substr(start, end - start), m_header, m_compressed,
                                        static_cast<std::size_t>(expected), m_source, array.location());
    }
    return decode_vtk_array(m_bytes.substr(start, end - start), m_header, m_compressed,
                            static_cast<std::size_t>(expected), m_source, start);
  }

  /// Checks format and that the ASCII text can hold `values` numbers; returns the format.
  std::string format_of(const XmlElement& array, std::size_t values) const {
    const std::string format = attribute(array, "format");
    if (format != "ascii" && format != "binary" && format != "appended") {
      fail(array, "DataArray format '" + format + "' is not ascii, binary or appended");
    }
    if (format == "ascii" && values > 0 && array.text.size() < 2 * values - 1) {
      fail(array, "ASCII array is too short for " + std::to_string(values) + " values");
    }
    return format;
  }

  std::vector<double> reals(const XmlElement& array, std::size_t tuples, std::size_t components) const {
    if (components_of(array) != components) {
      fail(array,
           "array has " + std::to_string(components_of(array)) + " components, expected " + std::to_string(components));
    }
    const TypeInfo& type = type_of(array);
    const std::size_t values = tuples * components;
    const std::string format = format_of(array, values);
    std::vector<double> out;
    if (format == "ascii") {
      out.reserve(values);
      TextCursor text(array.text, m_source);
      while (true) {
        text.skip_whitespace();
        if (text.at_end()) break;
        const std::string_view token = text.token("value");
        double value = 0.0;
        if (!parse_double(token, value)) fail(array, "value " + std::to_string(out.size()) + " is not a number");
        if (type.type == ValueType::float32) value = static_cast<float>(value);  // what the file's type holds
        if (out.size() == values) fail(array, "ASCII array has more than " + std::to_string(values) + " values");
        out.push_back(value);
      }
      if (out.size() != values) {
        fail(array, "ASCII array has " + std::to_string(out.size()) + " values, expected " + std::to_string(values));
      }
      return out;
    }
    const std::string bytes = binary_bytes(array, format, values, type);
    out.resize(values);
    for (std::size_t i = 0; i < values; ++i) out[i] = real_at(bytes, i, type);
    return out;
  }

  std::vector<std::int64_t> integers(const XmlElement& array, std::size_t values) const {
    if (components_of(array) != 1) fail(array, "array must have 1 component");
    const TypeInfo& type = type_of(array);
    if (is_real(type.type)) fail(array, "array must have an integer type, not " + std::string(type.name));
    const std::string format = format_of(array, values);
    std::vector<std::int64_t> out;
    if (format == "ascii") {
      out.reserve(values);
      TextCursor text(array.text, m_source);
      while (true) {
        text.skip_whitespace();
        if (text.at_end()) break;
        const std::string_view token = text.token("value");
        std::int64_t value = 0;
        if (!parse_integer(token, value)) fail(array, "value " + std::to_string(out.size()) + " is not an integer");
        if (out.size() == values) fail(array, "ASCII array has more than " + std::to_string(values) + " values");
        out.push_back(value);
      }
      if (out.size() != values) {
        fail(array, "ASCII array has " + std::to_string(out.size()) + " values, expected " + std::to_string(values));
      }
      return out;
    }
    const std::string bytes = binary_bytes(array, format, values, type);
    out.resize(values);
    for (std::size_t i = 0; i < values; ++i) {
      if (!integer_at(bytes, i, type, out[i])) fail(array, "value " + std::to_string(i) + " exceeds Int64");
    }
    return out;
  }

  const XmlElement& named_array(const XmlElement& parent, const char* name) const {
    for (const XmlElement& c : parent.children) {
      const std::string* n = c.attribute("Name");
      if (c.name == "DataArray" && n && *n == name) return c;
    }
    fail(parent, std::string("<") + parent.name + "> has no DataArray named '" + name + "'");
  }

  void read_cells(const XmlElement& element, std::size_t cells, std::size_t points, const CellKind& kind,
                  std::vector<Index>& out) const {
    const XmlElement& types_array = named_array(element, "types");
    const std::vector<std::int64_t> types = integers(types_array, cells);
    for (std::size_t c = 0; c < cells; ++c) {
      if (types[c] != kind.vtk_type) {
        fail(types_array, "cell " + std::to_string(c) + " has VTK cell type " + std::to_string(types[c]) + "; only " +
                              kind.name + " are read here");
      }
    }
    const auto n = static_cast<std::size_t>(kind.nodes);
    const XmlElement& offsets_array = named_array(element, "offsets");
    const std::vector<std::int64_t> offsets = integers(offsets_array, cells);
    for (std::size_t c = 0; c < cells; ++c) {
      if (offsets[c] != static_cast<std::int64_t>(n * (c + 1))) {
        fail(offsets_array, "offset of cell " + std::to_string(c) + " is " + std::to_string(offsets[c]) +
                                ", expected " + std::to_string(n * (c + 1)) + " for " + kind.name);
      }
    }
    const XmlElement& connectivity_array = named_array(element, "connectivity");
    const std::vector<std::int64_t> connectivity = integers(connectivity_array, n * cells);
    out.resize(connectivity.size());
    for (std::size_t i = 0; i < connectivity.size(); ++i) {
      if (connectivity[i] < 0 || static_cast<std::uint64_t>(connectivity[i]) >= points) {
        fail(connectivity_array, "point index " + std::to_string(connectivity[i]) + " of cell " +
                                     std::to_string(i / n) + " is out of range (there are " + std::to_string(points) +
                                     " points)");
      }
      out[i] = static_cast<Index>(connectivity[i]);
    }
  }

  void read_fields(const XmlElement& data, std::size_t tuples, FieldSet& fields, std::vector<int>* labels) const {
    std::set<std::string> seen;
    for (const XmlElement& array : data.children) {
      if (array.name != "DataArray") continue;
      const std::string name = attribute(array, "Name");
      if (!seen.insert(name).second) fail(array, "two arrays are named '" + name + "'");
      const std::size_t components = components_of(array);
      if (labels && name == "label" && components == 1 && !is_real(type_of(array).type)) {
        const std::vector<std::int64_t> values = integers(array, tuples);
        labels->resize(tuples);
        for (std::size_t i = 0; i < tuples; ++i) {
          if (values[i] < INT32_MIN || values[i] > INT32_MAX) fail(array, "label " + std::to_string(i) + " overflows");
          (*labels)[i] = static_cast<int>(values[i]);
        }
        continue;
      }
      if (components != 1 && components != 3) {
        fail(array, "array '" + name + "' has " + std::to_string(components) +
                        " components; only scalars (1) and vectors (3) are supported");
      }
      const std::vector<double> values = reals(array, tuples, components);
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::isnan(values[i])) fail(array, "value " + std::to_string(i) + " of array '" + name + "' is NaN");
      }
      if (components == 1) {
        fields.scalars[name] = values;
      } else {
        std::vector<Vec3> vectors(tuples);
        for (std::size_t i = 0; i < tuples; ++i) vectors[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
        fields.vectors[name] = std::move(vectors);
      }
    }
  }

  std::string_view m_bytes;
  std::string m_source;
  XmlDocument m_doc;
  VtkHeaderType m_header = VtkHeaderType::uint32;
  bool m_compressed = false;
  bool m_appended_base64 = false;
};

}  // namespace

TetMesh read_vtu(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  return parse_vtu(bytes, path.string());
}

TetMesh parse_vtu(std::string_view bytes, const std::string& source) {
  VtuGrid grid = VtuReader(bytes, source).read({vtk_tetra, 4, "tetrahedra (VTK_TETRA = 10)"});
  TetMesh mesh;
  mesh.positions = std::move(grid.positions);
  mesh.tets.resize(grid.cells.size() / 4);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    for (std::size_t k = 0; k < 4; ++k) mesh.tets[t][k] = grid.cells[4 * t + k];
  mesh.vertex_fields = std::move(grid.point_fields);
  mesh.tet_fields = std::move(grid.cell_fields);
  mesh.tet_labels = std::move(grid.labels);
  mesh.validate(source);
  return mesh;
}

TriMesh read_vtu_surface(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  return parse_vtu_surface(bytes, path.string());
}

TriMesh parse_vtu_surface(std::string_view bytes, const std::string& source) {
  VtuGrid grid = VtuReader(bytes, source).read({vtk_triangle, 3, "triangles (VTK_TRIANGLE = 5)"});
  TriMesh mesh;
  mesh.positions = std::move(grid.positions);
  mesh.triangles.resize(grid.cells.size() / 3);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) mesh.triangles[t][k] = grid.cells[3 * t + k];
  mesh.vertex_fields = std::move(grid.point_fields);
  mesh.triangle_fields = std::move(grid.cell_fields);
  mesh.triangle_labels = std::move(grid.labels);
  auto normals = mesh.vertex_fields.vectors.find("Normals");
  if (normals != mesh.vertex_fields.vectors.end()) {
    mesh.normals = std::move(normals->second);
    mesh.vertex_fields.vectors.erase(normals);
  }
  mesh.validate(source);
  return mesh;
}

}  // namespace forensim
