#include "tet_io/vtu_writer.hpp"

#include <cstring>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "tet_io/number_text.hpp"
#include "tet_io/xml_lite.hpp"

namespace forensim {
namespace {

constexpr std::uint8_t vtk_triangle = 5;
constexpr std::uint8_t vtk_tetra = 10;

enum class ArrayType { float64, float32, int32, int64, uint8 };

const char* type_name(ArrayType type) {
  switch (type) {
    case ArrayType::float64:
      return "Float64";
    case ArrayType::float32:
      return "Float32";
    case ArrayType::int32:
      return "Int32";
    case ArrayType::int64:
      return "Int64";
    case ArrayType::uint8:
      return "UInt8";
  }
  return "";
}

/// One DataArray: its values already in the file's binary type (little-endian).
struct ArrayOut {
  std::string name;
  ArrayType type;
  int components;
  std::string bytes;
};

template <class T>
void append_value(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

void append_real(std::string& bytes, double value, ArrayType type) {
  if (type == ArrayType::float32) {
    append_value(bytes, static_cast<float>(value));
  } else {
    append_value(bytes, value);
  }
}

ArrayType real_type(VtuPrecision precision) {
  return precision == VtuPrecision::float32 ? ArrayType::float32 : ArrayType::float64;
}

ArrayOut scalar_array(const std::string& name, const std::vector<double>& values, ArrayType type) {
  ArrayOut a{name, type, 1, {}};
  a.bytes.reserve(values.size() * 8);
  for (double v : values) append_real(a.bytes, v, type);
  return a;
}

ArrayOut vector_array(const std::string& name, const std::vector<Vec3>& values, ArrayType type) {
  ArrayOut a{name, type, 3, {}};
  a.bytes.reserve(values.size() * 24);
  for (const Vec3& v : values) {
    for (int k = 0; k < 3; ++k) append_real(a.bytes, v[k], type);
  }
  return a;
}

void add_fields(std::vector<ArrayOut>& arrays, const FieldSet& fields, ArrayType type) {
  for (const auto& [name, values] : fields.scalars) arrays.push_back(scalar_array(name, values, type));
  for (const auto& [name, values] : fields.vectors) arrays.push_back(vector_array(name, values, type));
}

/// Appends the decimal text of an array, one tuple per line.
void append_ascii(std::string& out, const ArrayOut& a, const std::string& indent) {
  const std::size_t size = a.type == ArrayType::float64 || a.type == ArrayType::int64 ? 8
                           : a.type == ArrayType::uint8                               ? 1
                                                                                      : 4;
  const std::size_t count = a.bytes.size() / size;
  for (std::size_t i = 0; i < count; ++i) {
    if (i % static_cast<std::size_t>(a.components) == 0) {
      if (i > 0) out += '\n';
      out += indent;
    } else {
      out += ' ';
    }
    const char* p = a.bytes.data() + i * size;
    switch (a.type) {
      case ArrayType::float64: {
        double v;
        std::memcpy(&v, p, 8);
        append_double(out, v);
        break;
      }
      case ArrayType::float32: {
        float v;
        std::memcpy(&v, p, 4);
        append_float(out, v);
        break;
      }
      case ArrayType::int32: {
        std::int32_t v;
        std::memcpy(&v, p, 4);
        append_integer(out, v);
        break;
      }
      case ArrayType::int64: {
        std::int64_t v;
        std::memcpy(&v, p, 8);
        append_integer(out, v);
        break;
      }
      case ArrayType::uint8:
        append_integer(out, static_cast<unsigned char>(*p));
        break;
    }
  }
  if (count > 0) out += '\n';
}

/// The pieces of one unstructured grid, in file order.
struct Grid {
  std::size_t point_count = 0, cell_count = 0;
  std::vector<ArrayOut> point_data, cell_data;
  ArrayOut points, connectivity, offsets, types;
};

class VtuFileWriter {
 public:
  VtuFileWriter(const Grid& grid, const VtuOptions& options) : m_grid(grid), m_options(options) {}

  void write(const std::filesystem::path& path) {
    const bool binary = m_options.encoding != VtuEncoding::ascii;
    m_compress = binary && m_options.compress;
    const bool appended = m_options.encoding == VtuEncoding::appended_raw;
    m_xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"";
    m_xml += m_options.header_type == VtkHeaderType::uint64 ? " header_type=\"UInt64\"" : " header_type=\"UInt32\"";
    if (m_compress) m_xml += " compressor=\"vtkZLibDataCompressor\"";
    m_xml += ">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" + std::to_string(m_grid.point_count) +
             "\" NumberOfCells=\"" + std::to_string(m_grid.cell_count) + "\">\n";
    data_section("PointData", m_grid.point_data);
    data_section("CellData", m_grid.cell_data);
    m_xml += "      <Points>\n";
    array(m_grid.points);
    m_xml += "      </Points>\n      <Cells>\n";
    array(m_grid.connectivity);
    array(m_grid.offsets);
    array(m_grid.types);
    m_xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    AtomicFile file(path);
    if (appended) {
      m_xml += "  <AppendedData encoding=\"raw\">\n   _";
      file.stream().write(m_xml.data(), static_cast<std::streamsize>(m_xml.size()));
      for (const VtkEncodedArray& e : m_appended) {
        file.stream().write(e.header.data(), static_cast<std::streamsize>(e.header.size()));
        file.stream().write(e.payload.data(), static_cast<std::streamsize>(e.payload.size()));
      }
      const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
      file.stream().write(tail.data(), static_cast<std::streamsize>(tail.size()));
    } else {
      m_xml += "</VTKFile>\n";
      file.stream().write(m_xml.data(), static_cast<std::streamsize>(m_xml.size()));
    }
    file.commit();
  }

 private:
  void data_section(const char* tag, const std::vector<ArrayOut>& arrays) {
    if (arrays.empty()) return;
    m_xml += "      <" + std::string(tag);
    // Active attributes: what ParaView colours by first.
    for (const ArrayOut& a : arrays) {
      if (a.components == 1) {
        m_xml += " Scalars=\"" + xml_escape(a.name) + "\"";
        break;
      }
    }
    for (const ArrayOut& a : arrays) {
      if (a.components == 3) {
        m_xml += " Vectors=\"" + xml_escape(a.name) + "\"";
        break;
      }
    }
    m_xml += ">\n";
    for (const ArrayOut& a : arrays) array(a);
    m_xml += "      </" + std::string(tag) + ">\n";
  }

  void array(const ArrayOut& a) {
    m_xml += "        <DataArray type=\"" + std::string(type_name(a.type)) + "\" Name=\"" + xml_escape(a.name) + "\"";
    if (a.components != 1) m_xml += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
    switch (m_options.encoding) {
      case VtuEncoding::ascii:
        m_xml += " format=\"ascii\">\n";
        append_ascii(m_xml, a, "          ");
        m_xml += "        </DataArray>\n";
        break;
      case VtuEncoding::inline_base64: {
        const VtkEncodedArray e = encode_vtk_array(a.bytes, m_options.header_type, m_compress, m_options.zlib_level);
        m_xml += " format=\"binary\">\n          " + vtk_array_to_base64(e, m_compress) + "\n        </DataArray>\n";
        break;
      }
      case VtuEncoding::appended_raw: {
        m_xml += " format=\"appended\" offset=\"" + std::to_string(m_offset) + "\"/>\n";
        m_appended.push_back(encode_vtk_array(a.bytes, m_options.header_type, m_compress, m_options.zlib_level));
        m_offset += m_appended.back().header.size() + m_appended.back().payload.size();
        break;
      }
    }
  }

  const Grid& m_grid;
  const VtuOptions& m_options;
  bool m_compress = false;
  std::string m_xml;
  std::vector<VtkEncodedArray> m_appended;
  std::size_t m_offset = 0;
};

template <std::size_t N>
void fill_cells(Grid& grid, const std::vector<std::array<Index, N>>& cells, std::uint8_t type) {
  grid.cell_count = cells.size();
  grid.connectivity = {"connectivity", ArrayType::int64, 1, {}};
  grid.offsets = {"offsets", ArrayType::int64, 1, {}};
  grid.types = {"types", ArrayType::uint8, 1, {}};
  grid.connectivity.bytes.reserve(cells.size() * N * 8);
  grid.offsets.bytes.reserve(cells.size() * 8);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (Index v : cells[c]) append_value<std::int64_t>(grid.connectivity.bytes, v);
    append_value<std::int64_t>(grid.offsets.bytes, static_cast<std::int64_t>((c + 1) * N));
  }
  grid.types.bytes.assign(cells.size(), static_cast<char>(type));
}

void fill_points(Grid& grid, const std::vector<Vec3>& positions, const VtuOptions& options) {
  grid.point_count = positions.size();
  grid.points = vector_array("Points", positions, real_type(options.point_precision));
}

ArrayOut label_array(const std::vector<int>& labels) {
  ArrayOut a{"label", ArrayType::int32, 1, {}};
  for (int label : labels) append_value<std::int32_t>(a.bytes, label);
  return a;
}

void check_no_label_field(const FieldSet& fields, const std::string& source, const char* kind) {
  if (fields.scalars.count("label") || fields.vectors.count("label")) {
    throw InputError(source, std::string(kind) + " field 'label'", "clashes with the cell array of region labels");
  }
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const TetMesh& mesh, const VtuOptions& options) {
  const std::string source = "mesh written to " + path.string();
  mesh.validate(source);
  check_no_label_field(mesh.tet_fields, source, "tet");
  Grid grid;
  fill_points(grid, mesh.positions, options);
  fill_cells(grid, mesh.tets, vtk_tetra);
  const ArrayType type = real_type(options.field_precision);
  add_fields(grid.point_data, mesh.vertex_fields, type);
  std::vector<int> labels(mesh.tet_count());
  for (std::size_t t = 0; t < labels.size(); ++t) labels[t] = mesh.label(t);
  grid.cell_data.push_back(label_array(labels));
  add_fields(grid.cell_data, mesh.tet_fields, type);
  VtuFileWriter(grid, options).write(path);
}

void write_vtu(const std::filesystem::path& path, const TriMesh& mesh, const VtuOptions& options) {
  const std::string source = "mesh written to " + path.string();
  mesh.validate(source);
  check_no_label_field(mesh.triangle_fields, source, "triangle");
  Grid grid;
  fill_points(grid, mesh.positions, options);
  fill_cells(grid, mesh.triangles, vtk_triangle);
  const ArrayType type = real_type(options.field_precision);
  add_fields(grid.point_data, mesh.vertex_fields, type);
  if (mesh.has_normals()) grid.point_data.push_back(vector_array("Normals", mesh.normals, type));
  if (!mesh.triangle_labels.empty()) grid.cell_data.push_back(label_array(mesh.triangle_labels));
  add_fields(grid.cell_data, mesh.triangle_fields, type);
  VtuFileWriter(grid, options).write(path);
}

}  // namespace forensim
