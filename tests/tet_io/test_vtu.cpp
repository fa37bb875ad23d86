#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <map>

#include "core/error.hpp"
#include "geometry/primitives.hpp"
#include "support/test_support.hpp"
#include "tet_io/sample_tet_mesh.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"
#include "tet_io/xml_lite.hpp"

using namespace forensim;
using forensim::test::sample_tet_mesh;

namespace {

struct Case {
  const char* name;
  VtuOptions options;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  VtuOptions o;
  o.encoding = VtuEncoding::ascii;
  cases.push_back({"ascii", o});
  o.encoding = VtuEncoding::inline_base64;
  cases.push_back({"base64", o});
  o.compress = true;
  cases.push_back({"base64_zlib", o});
  o.encoding = VtuEncoding::appended_raw;
  o.compress = false;
  cases.push_back({"appended", o});
  o.compress = true;
  cases.push_back({"appended_zlib", o});
  o.header_type = VtkHeaderType::uint32;
  cases.push_back({"appended_zlib_uint32", o});
  o.compress = false;
  cases.push_back({"appended_uint32", o});
  o.encoding = VtuEncoding::inline_base64;
  cases.push_back({"base64_uint32", o});
  o.compress = true;
  cases.push_back({"base64_zlib_uint32", o});
  return cases;
}

/// name="value" pairs of one start tag (plain string scanning: independent of forensim's XML reader).
std::map<std::string, std::string> attributes_of(const std::string& tag) {
  std::map<std::string, std::string> out;
  std::size_t at = 0;
  while ((at = tag.find("=\"", at)) != std::string::npos) {
    std::size_t name_begin = at;
    while (name_begin > 0 &&
           (std::isalnum(static_cast<unsigned char>(tag[name_begin - 1])) || tag[name_begin - 1] == '_')) {
      --name_begin;
    }
    const std::size_t close = tag.find('"', at + 2);
    out[tag.substr(name_begin, at - name_begin)] = tag.substr(at + 2, close - at - 2);
    at = close + 1;
  }
  return out;
}

std::size_t type_size(const std::string& type) {
  if (type == "Float64" || type == "Int64" || type == "UInt64") return 8;
  if (type == "Float32" || type == "Int32" || type == "UInt32") return 4;
  if (type == "UInt8" || type == "Int8") return 1;
  ADD_FAILURE() << "unexpected type " << type;
  return 1;
}

std::uint64_t word(const std::string& bytes, std::size_t at, std::size_t size) {
  EXPECT_LE(at + size, bytes.size());
  if (at + size > bytes.size()) return 0;
  std::uint64_t v = 0;
  std::memcpy(&v, bytes.data() + at, size);  // little-endian host
  return v;
}

/// Checks what ParaView's reader relies on, without forensim's own XML parser: the VTKFile header attributes,
/// and that each appended array starts exactly at its offset attribute, holds tuples * components * size bytes
/// (after decompression) and that the arrays tile the appended block.
void check_appended_layout(const std::string& file, std::size_t nodes_per_cell, bool compressed, std::size_t header) {
  const std::size_t root_at = file.find("<VTKFile");
  ASSERT_NE(root_at, std::string::npos);
  const auto root = attributes_of(file.substr(root_at, file.find('>', root_at) - root_at));
  EXPECT_EQ(root.at("type"), "UnstructuredGrid");
  EXPECT_TRUE(root.at("version") == "1.0" || root.at("version") == "0.1");
  EXPECT_EQ(root.at("byte_order"), "LittleEndian");
  EXPECT_EQ(root.at("header_type"), header == 8 ? "UInt64" : "UInt32");
  EXPECT_EQ(root.count("compressor"), compressed ? 1u : 0u);
  const std::size_t piece_at = file.find("<Piece");
  const auto piece = attributes_of(file.substr(piece_at, file.find('>', piece_at) - piece_at));
  const std::size_t points = std::stoul(piece.at("NumberOfPoints"));
  const std::size_t cells = std::stoul(piece.at("NumberOfCells"));
  const std::size_t appended_tag = file.find("<AppendedData encoding=\"raw\">");
  ASSERT_NE(appended_tag, std::string::npos);
  const std::size_t begin = file.find('_', appended_tag) + 1;
  const std::size_t end = file.rfind("\n  </AppendedData>");
  ASSERT_LT(begin, end);
  const std::string data = file.substr(begin, end - begin);
  const std::size_t cell_data_begin = file.find("<CellData"), cell_data_end = file.find("</CellData>");

  std::size_t position = 0, arrays = 0;
  const std::string xml = file.substr(0, appended_tag);
  for (std::size_t at = xml.find("<DataArray"); at != std::string::npos; at = xml.find("<DataArray", at + 1)) {
    const auto a = attributes_of(xml.substr(at, xml.find('>', at) - at));
    const std::string& name = a.at("Name");
    EXPECT_EQ(a.at("format"), "appended") << name;
    std::size_t tuples = (at > cell_data_begin && at < cell_data_end) ? cells : points;
    if (name == "connectivity") tuples = nodes_per_cell * cells;
    if (name == "offsets" || name == "types") tuples = cells;
    const std::size_t components = a.count("NumberOfComponents") ? std::stoul(a.at("NumberOfComponents")) : 1;
    const std::size_t expected = tuples * components * type_size(a.at("type"));
    EXPECT_EQ(std::stoul(a.at("offset")), position) << name;
    if (!compressed) {
      EXPECT_EQ(word(data, position, header), expected) << name;
      position += header + expected;
    } else {
      const std::uint64_t blocks = word(data, position, header);
      const std::uint64_t block_size = word(data, position + header, header);
      const std::uint64_t last = word(data, position + 2 * header, header);
      const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block_size + (last ? last : block_size);
      EXPECT_EQ(total, expected) << name;
      std::uint64_t compressed_bytes = 0;
      for (std::uint64_t b = 0; b < blocks; ++b) compressed_bytes += word(data, position + (3 + b) * header, header);
      position += (3 + blocks) * header + compressed_bytes;
    }
    ++arrays;
  }
  EXPECT_GE(arrays, 4u);
  EXPECT_EQ(position, data.size()) << "appended arrays do not tile the appended block";
}

}  // namespace

TEST(Vtu, RoundTripInEveryEncoding) {
  const TetMesh mesh = sample_tet_mesh();
  const auto dir = test::scratch_dir("vtu");
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const auto path = dir / (std::string(c.name) + ".vtu");
    write_vtu(path, mesh, c.options);
    const TetMesh back = read_vtu(path);
    test::expect_same_geometry(mesh, back);
    test::expect_same_fields(mesh.vertex_fields, back.vertex_fields);
    test::expect_same_fields(mesh.tet_fields, back.tet_fields);
  }
}

TEST(Vtu, Float32KeepsFloatPrecision) {
  const TetMesh mesh = sample_tet_mesh();
  VtuOptions o;
  o.point_precision = VtuPrecision::float32;
  o.field_precision = VtuPrecision::float32;
  for (VtuEncoding encoding : {VtuEncoding::ascii, VtuEncoding::appended_raw}) {
    o.encoding = encoding;
    const auto path = test::scratch_dir("vtu") / "f32.vtu";
    write_vtu(path, mesh, o);
    const TetMesh back = read_vtu(path);
    test::expect_same_geometry(mesh, back, true);
    test::expect_same_fields(mesh.vertex_fields, back.vertex_fields, true);
    test::expect_same_fields(mesh.tet_fields, back.tet_fields, true);
  }
}

TEST(Vtu, MultiBlockZlibRoundTripAndAppendedOffsetsMatch) {
  const TetMesh mesh = sample_tet_mesh(10, 10, 10);  // connectivity: 6000 * 4 * 8 bytes = 6 zlib blocks
  const auto dir = test::scratch_dir("vtu");
  for (const Case& c : all_cases()) {
    if (c.options.encoding != VtuEncoding::appended_raw) continue;
    SCOPED_TRACE(c.name);
    const auto path = dir / (std::string(c.name) + ".vtu");
    write_vtu(path, mesh, c.options);
    check_appended_layout(test::slurp(path), 4, c.options.compress,
                          c.options.header_type == VtkHeaderType::uint64 ? 8 : 4);
    const TetMesh back = read_vtu(path);
    test::expect_same_geometry(mesh, back);
    test::expect_same_fields(mesh.tet_fields, back.tet_fields);
  }
}

TEST(Vtu, CompressionShrinksFields) {
  TetMesh mesh = sample_tet_mesh(10, 10, 10);
  mesh.vertex_fields.scalars["moisture"].assign(mesh.vertex_count(), 0.8);  // constant field compresses well
  const auto dir = test::scratch_dir("vtu");
  VtuOptions raw, zlib;
  zlib.compress = true;
  write_vtu(dir / "raw.vtu", mesh, raw);
  write_vtu(dir / "zlib.vtu", mesh, zlib);
  EXPECT_LT(std::filesystem::file_size(dir / "zlib.vtu"), std::filesystem::file_size(dir / "raw.vtu"));
}

TEST(Vtu, TextEncodingsAreWellFormedXml) {
  const TetMesh mesh = sample_tet_mesh(1, 1, 2);
  for (const Case& c : all_cases()) {
    if (c.options.encoding == VtuEncoding::appended_raw) continue;
    SCOPED_TRACE(c.name);
    const auto path = test::scratch_dir("vtu") / "t.vtu";
    write_vtu(path, mesh, c.options);
    const std::string text = test::slurp(path);
    const XmlDocument doc = parse_xml(text, path.string());
    EXPECT_FALSE(doc.appended.has_value());
    const XmlElement* piece = doc.root.child("UnstructuredGrid")->child("Piece");
    ASSERT_NE(piece, nullptr);
    EXPECT_EQ(*piece->attribute("NumberOfCells"), std::to_string(mesh.tet_count()));
    EXPECT_EQ(*piece->child("CellData")->attribute("Scalars"), "label");
  }
}

TEST(Vtu, TriangleMeshWritesTriangleCells) {
  TriMesh mesh = make_icosphere(Vec3::Zero(), 2.0, 1);
  mesh.triangle_labels.assign(mesh.triangle_count(), 3);
  mesh.vertex_fields.scalars["darkening"].assign(mesh.vertex_count(), 0.25);
  mesh.normals = mesh.positions;
  for (Vec3& n : mesh.normals) n.normalize();
  const auto path = test::scratch_dir("vtu") / "skin.vtu";
  VtuOptions o;
  o.compress = true;
  write_vtu(path, mesh, o);
  const std::string file = test::slurp(path);
  check_appended_layout(file, 3, true, 8);
  EXPECT_NE(file.find("Name=\"Normals\" NumberOfComponents=\"3\""), std::string::npos);
  try {
    read_vtu(path);
    FAIL() << "triangles accepted as tets";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("VTK cell type 5"), std::string::npos) << e.what();
  }
  // Read back as a surface in every encoding: same vertices in the same order, normals, labels, fields.
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const auto each = test::scratch_dir("vtu") / (std::string("skin_") + c.name + ".vtu");
    write_vtu(each, mesh, c.options);
    const TriMesh back = read_vtu_surface(each);
    ASSERT_EQ(back.vertex_count(), mesh.vertex_count());
    ASSERT_EQ(back.triangles, mesh.triangles);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_LT((back.positions[v] - mesh.positions[v]).norm(), 1e-6);
      EXPECT_LT((back.normals[v] - mesh.normals[v]).norm(), 1e-6);
    }
    EXPECT_EQ(back.triangle_labels, mesh.triangle_labels);
    test::expect_same_fields(mesh.vertex_fields, back.vertex_fields);
  }
  // A tet file is not a surface.
  const auto tets = test::scratch_dir("vtu") / "tets.vtu";
  write_vtu(tets, sample_tet_mesh());
  EXPECT_THROW(read_vtu_surface(tets), InputError);
}

TEST(Vtu, RejectsLabelFieldClash) {
  TetMesh mesh = sample_tet_mesh(1, 1, 1);
  mesh.tet_fields.scalars["label"].assign(mesh.tet_count(), 1.0);
  EXPECT_THROW(write_vtu(test::scratch_dir("vtu") / "x.vtu", mesh), InputError);
}

TEST(Vtu, ReadsHandWrittenVersion01Ascii) {
  const auto path = test::scratch_dir("vtu") / "old.vtu";
  test::spit(path, R"(<?xml version="1.0"?>
<!-- written by hand, VTK 5 style -->
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="4" NumberOfCells="1">
      <PointData Scalars="t">
        <DataArray type="Float32" Name="t" format="ascii">1 2 3 4.5</DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  0 1 0  0 0 1
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)");
  const TetMesh mesh = read_vtu(path);
  ASSERT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(mesh.tets[0], (Tet{0, 1, 2, 3}));
  EXPECT_EQ(mesh.vertex_fields.scalars.at("t")[3], 4.5);
  EXPECT_TRUE(mesh.tet_labels.empty());
}
