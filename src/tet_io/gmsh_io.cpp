#include "tet_io/gmsh_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "tet_io/number_text.hpp"
#include "tet_io/text_cursor.hpp"

namespace forensim {
namespace {

constexpr int gmsh_tet4 = 4;
constexpr std::int64_t max_index = INT32_MAX;

/// Nodes per element for Gmsh's element types (0 = unknown). Needed to skip non-tet blocks in binary files.
int element_node_count(int type) {
  switch (type) {
    case 1:
      return 2;
    case 2:
      return 3;
    case 3:
      return 4;
    case 4:
      return 4;
    case 5:
      return 8;
    case 6:
      return 6;
    case 7:
      return 5;
    case 8:
      return 3;
    case 9:
      return 6;
    case 10:
      return 9;
    case 11:
      return 10;
    case 12:
      return 27;
    case 13:
      return 18;
    case 14:
      return 14;
    case 15:
      return 1;
    case 16:
      return 8;
    case 17:
      return 20;
    case 18:
      return 15;
    case 19:
      return 13;
    case 20:
      return 9;
    case 21:
      return 10;
    case 22:
      return 12;
    case 23:
      return 15;
    case 24:
      return 15;
    case 25:
      return 21;
    case 26:
      return 4;
    case 27:
      return 5;
    case 28:
      return 6;
    case 29:
      return 20;
    case 30:
      return 35;
    case 31:
      return 56;
    case 92:
      return 64;
    case 93:
      return 125;
    default:
      return 0;
  }
}

/// Label encoded in a physical group name written by write_gmsh, if any.
std::optional<int> label_from_name(const std::string& name) {
  if (name == "flesh") return tissue_flesh;
  if (name == "bone") return tissue_bone;
  constexpr std::string_view prefix = "region_";
  if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0) {
    std::int64_t value = 0;
    if (parse_integer(std::string_view(name).substr(prefix.size()), value) && value >= INT32_MIN &&
        value <= INT32_MAX) {
      return static_cast<int>(value);
    }
  }
  return std::nullopt;
}

std::string name_of_label(int label) {
  if (label == tissue_flesh) return "flesh";
  if (label == tissue_bone) return "bone";
  return "region_" + std::to_string(label);
}

/// A $NodeData or $ElementData section as read; resolved to a field once nodes and tets are known.
struct RawField {
  bool on_nodes = true;
  std::string name;
  int components = 1;
  std::vector<std::uint64_t> tags;
  std::vector<double> values;  // components per tag
  std::size_t position = 0;    // byte offset of the section's first line, for error locations
};

struct RawTet {
  std::uint64_t tag;
  std::array<std::uint64_t, 4> nodes;
  int label;
  std::size_t position;  // byte offset of the element in the file, for error locations
};

class GmshReader {
 public:
  GmshReader(std::string_view bytes, const std::string& source) : m_in(bytes, source) {}

  TetMesh read() {
    while (true) {
      m_in.skip_whitespace();
      if (m_in.at_end()) break;
      const std::string section = trimmed(m_in.line());
      if (section.empty() || section[0] != '$') m_in.fail("expected a section such as $Nodes, found '" + section + "'");
      const std::string name = section.substr(1);
      if (name != "MeshFormat" && m_version == 0) m_in.fail("missing $MeshFormat before $" + name);
      if (name == "MeshFormat") {
        read_format();
      } else if (name == "PhysicalNames") {
        read_physical_names();
      } else if (name == "Entities") {
        m_binary ? read_entities_binary() : read_entities_ascii();
      } else if (name == "Nodes") {
        if (m_have_nodes) m_in.fail("second $Nodes section");
        m_have_nodes = true;
        if (m_version == 2) {
          read_nodes_v2();
        } else {
          m_binary ? read_nodes_binary() : read_nodes_ascii();
        }
      } else if (name == "Elements") {
        if (m_have_elements) m_in.fail("second $Elements section");
        m_have_elements = true;
        if (m_version == 2) {
          read_elements_v2();
        } else {
          m_binary ? read_elements_binary() : read_elements_ascii();
        }
      } else if (name == "NodeData" || name == "ElementData") {
        read_data(name == "NodeData");
      } else {
        skip_section(name);
        continue;
      }
      expect_end(name);
    }
    if (m_version == 0) m_in.fail("not a Gmsh MSH file: no $MeshFormat section");
    if (!m_have_nodes) m_in.fail("no $Nodes section");
    return build();
  }

 private:
  static std::string trimmed(std::string_view s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    constexpr std::size_t limit = 64;
    std::string out;
    for (char c : s.substr(0, limit)) out += (c >= 32 && c < 127) ? c : '?';
    return out;
  }

  void expect_end(const std::string& name) {
    m_in.skip_whitespace();
    if (m_in.at_end()) m_in.fail("missing $End" + name);
    const std::string end = trimmed(m_in.line());
    if (end != "$End" + name) m_in.fail("expected $End" + name + ", found '" + end + "'");
  }

  void skip_section(const std::string& name) {
    const std::string marker = "$End" + name;
    const std::size_t at = m_in.bytes().find(marker, m_in.position());
    if (at == std::string_view::npos) m_in.fail("section $" + name + " has no " + marker);
    m_in.seek(at);
    m_in.line();
  }

  /// Fails unless `count` items of at least `bytes_each` bytes fit in what remains of the file.
  void check_count(std::uint64_t count, std::size_t bytes_each, const char* what) {
    if (count > m_in.remaining() / bytes_each) {
      const std::string problem = std::string(what) + " count " + std::to_string(count) +
                                  " cannot fit in the remaining " + std::to_string(m_in.remaining()) + " bytes";
      m_binary ? m_in.fail_binary(problem) : m_in.fail(problem);
    }
  }

  void read_format() {
    if (m_version != 0) m_in.fail("second $MeshFormat section");
    const std::string_view version = m_in.token("MSH version");
    const std::int64_t file_type = m_in.integer("file type", 0, 1);
    const std::int64_t data_size = m_in.integer("data size", 0, 64);
    if (version == "4.1") {
      m_version = 4;
    } else if (version == "2.2" || version == "2.1" || version == "2" || version == "2.0") {
      m_version = 2;
    } else {
      m_in.fail("unsupported MSH version '" + trimmed(version) + "' (supported: 4.1, 2.2)");
    }
    m_binary = file_type == 1;
    if (m_binary && m_version == 2) m_in.fail("binary MSH 2.2 is not supported; save as MSH 4.1 or ASCII");
    if (m_binary) {
      if (data_size != 8) m_in.fail("binary MSH with data size " + std::to_string(data_size) + " is not supported");
      m_in.line();  // rest of the version line, then the binary integer 1 marking the byte order
      const auto one = m_in.binary<std::int32_t>("byte-order marker");
      if (one != 1) {
        m_in.fail_binary(one == 0x01000000 ? "big-endian binary MSH is not supported"
                                           : "bad byte-order marker in binary $MeshFormat");
      }
    }
  }

  void read_physical_names() {
    const std::int64_t count = m_in.integer("physical name count", 0, INT32_MAX);
    check_count(static_cast<std::uint64_t>(count), 6, "physical name");
    for (std::int64_t i = 0; i < count; ++i) {
      const int dim = static_cast<int>(m_in.integer("physical dimension", 0, 3));
      const int tag = static_cast<int>(m_in.integer("physical tag", INT32_MIN, INT32_MAX));
      std::string_view rest = m_in.line();
      const std::size_t open = rest.find('"');
      const std::size_t close = open == std::string_view::npos ? open : rest.find('"', open + 1);
      if (close == std::string_view::npos) m_in.fail("physical name is not in double quotes");
      m_physical_names[{dim, tag}] = std::string(rest.substr(open + 1, close - open - 1));
    }
  }

  // ---- $Entities (4.1): only volume entities' first physical tag matters.
  void read_entities_ascii() {
    std::array<std::int64_t, 4> counts{};
    for (auto& c : counts) c = m_in.integer("entity count", 0, INT64_MAX);
    for (int dim = 0; dim < 4; ++dim) {
      for (std::int64_t e = 0; e < counts[dim]; ++e) {
        const int tag = static_cast<int>(m_in.integer("entity tag", INT32_MIN, INT32_MAX));
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) m_in.finite_double("entity bounding box");
        const std::int64_t physical_count = m_in.integer("physical tag count", 0, INT64_MAX);
        std::optional<int> first;
        for (std::int64_t p = 0; p < physical_count; ++p) {
          const int physical = static_cast<int>(m_in.integer("physical tag", INT32_MIN, INT32_MAX));
          if (!first) first = physical;
        }
        if (dim > 0) {
          const std::int64_t bounding = m_in.integer("bounding entity count", 0, INT64_MAX);
          for (std::int64_t b = 0; b < bounding; ++b) m_in.integer("bounding entity tag", INT32_MIN, INT32_MAX);
        }
        if (dim == 3 && first) m_volume_physical[tag] = *first;
      }
    }
  }

  void read_entities_binary() {
    std::array<std::uint64_t, 4> counts{};
    for (auto& c : counts) c = m_in.binary<std::uint64_t>("entity count");
    for (int dim = 0; dim < 4; ++dim) {
      check_count(counts[dim], 4 + 24 + 8, "entity");
      for (std::uint64_t e = 0; e < counts[dim]; ++e) {
        const auto tag = m_in.binary<std::int32_t>("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) {
          if (!std::isfinite(m_in.binary<double>("entity bounding box"))) {
            m_in.fail_binary("entity bounding box is not finite");
          }
        }
        const auto physical_count = m_in.binary<std::uint64_t>("physical tag count");
        check_count(physical_count, 4, "physical tag");
        std::optional<int> first;
        for (std::uint64_t p = 0; p < physical_count; ++p) {
          const auto physical = m_in.binary<std::int32_t>("physical tag");
          if (!first) first = physical;
        }
        if (dim > 0) {
          const auto bounding = m_in.binary<std::uint64_t>("bounding entity count");
          check_count(bounding, 4, "bounding entity");
          m_in.raw(bounding * 4, "bounding entity tags");
        }
        if (dim == 3 && first) m_volume_physical[tag] = *first;
      }
    }
  }

  // ---- $Nodes
  void add_node(std::uint64_t tag, const Vec3& p) {
    if (m_positions.size() >= static_cast<std::size_t>(max_index)) m_in.fail("more than 2^31-1 nodes");
    const auto [it, inserted] = m_node_index.emplace(tag, static_cast<Index>(m_positions.size()));
    if (!inserted) {
      const std::string problem = "node tag " + std::to_string(tag) + " is defined twice";
      m_binary ? m_in.fail_binary(problem) : m_in.fail(problem);
    }
    m_positions.push_back(p);
  }

  void reserve_nodes(std::uint64_t count) {
    m_positions.reserve(count);
    m_node_index.reserve(count);
  }

  void read_nodes_ascii() {
    const std::int64_t blocks = m_in.integer("node block count", 0, INT64_MAX);
    const std::int64_t total = m_in.integer("node count", 0, max_index);
    m_in.integer("minimum node tag", 0, INT64_MAX);
    m_in.integer("maximum node tag", 0, INT64_MAX);
    check_count(static_cast<std::uint64_t>(blocks), 8, "node block");
    check_count(static_cast<std::uint64_t>(total), 8, "node");
    reserve_nodes(static_cast<std::uint64_t>(total));
    std::vector<std::uint64_t> tags;
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = m_in.integer("node block entity dimension", 0, 3);
      m_in.integer("node block entity tag", INT32_MIN, INT32_MAX);
      const std::int64_t parametric = m_in.integer("parametric flag", 0, 1);
      const std::int64_t count = m_in.integer("node block size", 0, total);
      if (static_cast<std::int64_t>(m_positions.size()) + count > total) {
        m_in.fail("node blocks hold more nodes than the declared " + std::to_string(total));
      }
      tags.resize(static_cast<std::size_t>(count));
      for (auto& t : tags) t = static_cast<std::uint64_t>(m_in.integer("node tag", 1, INT64_MAX));
      for (std::uint64_t t : tags) {
        Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = m_in.finite_double("node coordinate");
        if (parametric == 1) {
          for (std::int64_t k = 0; k < dim; ++k) m_in.finite_double("parametric coordinate");
        }
        add_node(t, p);
      }
    }
    if (static_cast<std::int64_t>(m_positions.size()) != total) {
      m_in.fail("node blocks hold " + std::to_string(m_positions.size()) + " nodes, the header declares " +
                std::to_string(total));
    }
  }

  void read_nodes_binary() {
    const auto blocks = m_in.binary<std::uint64_t>("node block count");
    const auto total = m_in.binary<std::uint64_t>("node count");
    m_in.binary<std::uint64_t>("minimum node tag");
    m_in.binary<std::uint64_t>("maximum node tag");
    check_count(blocks, 20, "node block");
    check_count(total, 32, "node");
    if (total > static_cast<std::uint64_t>(max_index)) m_in.fail_binary("more than 2^31-1 nodes");
    reserve_nodes(total);
    std::vector<std::uint64_t> tags;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const auto dim = m_in.binary<std::int32_t>("node block entity dimension");
      m_in.binary<std::int32_t>("node block entity tag");
      const auto parametric = m_in.binary<std::int32_t>("parametric flag");
      const auto count = m_in.binary<std::uint64_t>("node block size");
      if (dim < 0 || dim > 3 || parametric < 0 || parametric > 1) m_in.fail_binary("bad node block header");
      const std::size_t doubles_each = 3 + (parametric ? static_cast<std::size_t>(dim) : 0);
      check_count(count, 8 * (1 + doubles_each), "node");
      if (m_positions.size() + count > total) {
        m_in.fail_binary("node blocks hold more nodes than the declared " + std::to_string(total));
      }
      tags.resize(count);
      for (auto& t : tags) t = m_in.binary<std::uint64_t>("node tag");
      for (std::uint64_t t : tags) {
        Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = m_in.binary<double>("node coordinate");
        if (!p.allFinite()) m_in.fail_binary("node " + std::to_string(t) + " has a non-finite coordinate");
        m_in.raw(8 * (doubles_each - 3), "parametric coordinates");
        add_node(t, p);
      }
    }
    if (m_positions.size() != total) {
      m_in.fail_binary("node blocks hold " + std::to_string(m_positions.size()) + " nodes, the header declares " +
                       std::to_string(total));
    }
  }

  void read_nodes_v2() {
    const std::int64_t total = m_in.integer("node count", 0, max_index);
    check_count(static_cast<std::uint64_t>(total), 8, "node");
    reserve_nodes(static_cast<std::uint64_t>(total));
    for (std::int64_t i = 0; i < total; ++i) {
      const auto tag = static_cast<std::uint64_t>(m_in.integer("node tag", 1, INT64_MAX));
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = m_in.finite_double("node coordinate");
      add_node(tag, p);
    }
  }

  // ---- $Elements
  int label_of_physical(int physical) const {
    const auto it = m_physical_names.find({3, physical});
    if (it != m_physical_names.end()) {
      if (const auto label = label_from_name(it->second)) return *label;
    }
    return physical;
  }

  int label_of_entity(int entity) const {
    const auto it = m_volume_physical.find(entity);
    return it == m_volume_physical.end() ? entity : label_of_physical(it->second);
  }

  void read_elements_ascii() {
    const std::int64_t blocks = m_in.integer("element block count", 0, INT64_MAX);
    const std::int64_t total = m_in.integer("element count", 0, INT64_MAX);
    m_in.integer("minimum element tag", 0, INT64_MAX);
    m_in.integer("maximum element tag", 0, INT64_MAX);
    check_count(static_cast<std::uint64_t>(blocks), 8, "element block");
    check_count(static_cast<std::uint64_t>(total), 4, "element");
    std::int64_t seen = 0;
    for (std::int64_t b = 0; b < blocks; ++b) {
      m_in.integer("element block entity dimension", 0, 3);
      const int entity = static_cast<int>(m_in.integer("element block entity tag", INT32_MIN, INT32_MAX));
      const int type = static_cast<int>(m_in.integer("element type", 1, INT32_MAX));
      const std::int64_t count = m_in.integer("element block size", 0, total - seen);
      seen += count;
      m_in.line();
      const int label = label_of_entity(entity);
      for (std::int64_t e = 0; e < count; ++e) {
        m_in.skip_whitespace();
        if (type != gmsh_tet4) {
          if (m_in.at_end()) m_in.fail("unexpected end of file in $Elements");
          m_in.line();
          continue;
        }
        RawTet tet{};
        tet.position = m_in.position();
        tet.tag = static_cast<std::uint64_t>(m_in.integer("element tag", 1, INT64_MAX));
        for (auto& n : tet.nodes) n = static_cast<std::uint64_t>(m_in.integer("tet node tag", 1, INT64_MAX));
        if (!m_in.at_line_end()) m_in.fail("a linear tet (type 4) has more than 4 nodes");
        tet.label = label;
        m_tets.push_back(tet);
      }
    }
    if (seen != total) {
      m_in.fail("element blocks hold " + std::to_string(seen) + " elements, the header declares " +
                std::to_string(total));
    }
  }

  void read_elements_binary() {
    const auto blocks = m_in.binary<std::uint64_t>("element block count");
    const auto total = m_in.binary<std::uint64_t>("element count");
    m_in.binary<std::uint64_t>("minimum element tag");
    m_in.binary<std::uint64_t>("maximum element tag");
    check_count(blocks, 20, "element block");
    check_count(total, 16, "element");
    std::uint64_t seen = 0;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      m_in.binary<std::int32_t>("element block entity dimension");
      const auto entity = m_in.binary<std::int32_t>("element block entity tag");
      const auto type = m_in.binary<std::int32_t>("element type");
      const auto count = m_in.binary<std::uint64_t>("element block size");
      const int nodes = element_node_count(type);
      if (nodes == 0) m_in.fail_binary("unknown element type " + std::to_string(type) + " in binary $Elements");
      const std::size_t bytes_each = 8 * (1 + static_cast<std::size_t>(nodes));
      check_count(count, bytes_each, "element");
      if (count > total - seen) m_in.fail_binary("element blocks hold more elements than the declared total");
      seen += count;
      if (type != gmsh_tet4) {
        m_in.raw(count * bytes_each, "skipped elements");
        continue;
      }
      const int label = label_of_entity(entity);
      for (std::uint64_t e = 0; e < count; ++e) {
        RawTet tet{};
        tet.position = m_in.position();
        tet.tag = m_in.binary<std::uint64_t>("element tag");
        for (auto& n : tet.nodes) n = m_in.binary<std::uint64_t>("tet node tag");
        tet.label = label;
        m_tets.push_back(tet);
      }
    }
    if (seen != total) {
      m_in.fail_binary("element blocks hold " + std::to_string(seen) + " elements, the header declares " +
                       std::to_string(total));
    }
  }

  void read_elements_v2() {
    const std::int64_t total = m_in.integer("element count", 0, INT64_MAX);
    check_count(static_cast<std::uint64_t>(total), 8, "element");
    for (std::int64_t e = 0; e < total; ++e) {
      m_in.skip_whitespace();
      RawTet tet{};
      tet.position = m_in.position();
      tet.tag = static_cast<std::uint64_t>(m_in.integer("element tag", 1, INT64_MAX));
      const int type = static_cast<int>(m_in.integer("element type", 1, INT32_MAX));
      const std::int64_t tag_count = m_in.integer("element tag count", 0, 64);
      int physical = 0, elementary = 0;
      for (std::int64_t k = 0; k < tag_count; ++k) {
        const int value = static_cast<int>(m_in.integer("element tag", INT32_MIN, INT32_MAX));
        if (k == 0) physical = value;
        if (k == 1) elementary = value;
      }
      if (type != gmsh_tet4) {
        m_in.line();
        continue;
      }
      for (auto& n : tet.nodes) n = static_cast<std::uint64_t>(m_in.integer("tet node tag", 1, INT64_MAX));
      if (!m_in.at_line_end()) m_in.fail("a linear tet (type 4) has more than 4 nodes");
      tet.label = physical != 0 ? label_of_physical(physical) : elementary;
      m_tets.push_back(tet);
    }
  }

  // ---- $NodeData / $ElementData (same layout in 2.2 and 4.1; the values are binary in binary files)
  void read_data(bool on_nodes) {
    RawField field;
    field.on_nodes = on_nodes;
    m_in.skip_whitespace();
    field.position = m_in.position();
    const std::int64_t string_count = m_in.integer("string tag count", 0, 1000);
    for (std::int64_t i = 0; i < string_count; ++i) {
      m_in.skip_whitespace();
      std::string_view text = m_in.line();
      if (!text.empty() && text.front() == '"') {
        const std::size_t close = text.find('"', 1);
        if (close == std::string_view::npos) m_in.fail("string tag is not closed by a double quote");
        text = text.substr(1, close - 1);
      }
      if (i == 0) field.name = std::string(text);
    }
    const std::int64_t real_count = m_in.integer("real tag count", 0, 1000);
    for (std::int64_t i = 0; i < real_count; ++i) m_in.finite_double("real tag");
    const std::int64_t integer_count = m_in.integer("integer tag count", 3, 1000);
    std::int64_t count = 0;
    for (std::int64_t i = 0; i < integer_count; ++i) {
      if (i == 1)
        field.components = static_cast<int>(m_in.integer("component count", 1, 9));
      else if (i == 2)
        count = m_in.integer("data entry count", 0, INT32_MAX);
      else
        m_in.integer("integer tag", INT64_MIN, INT64_MAX);
    }
    const auto components = static_cast<std::size_t>(field.components);
    check_count(static_cast<std::uint64_t>(count), m_binary ? 4 + 8 * components : 2 * (1 + components), "data entry");
    field.tags.reserve(static_cast<std::size_t>(count));
    field.values.reserve(static_cast<std::size_t>(count) * components);
    if (m_binary) {
      m_in.line();  // end of the last integer tag's line; binary entries follow
      for (std::int64_t e = 0; e < count; ++e) {
        const auto tag = m_in.binary<std::int32_t>("data entry tag");
        if (tag <= 0) m_in.fail_binary("data entry tag " + std::to_string(tag) + " is not positive");
        field.tags.push_back(static_cast<std::uint64_t>(tag));
        for (std::size_t k = 0; k < components; ++k) {
          const auto value = m_in.binary<double>("data value");
          if (!std::isfinite(value)) m_in.fail_binary("value of field '" + field.name + "' is not finite");
          field.values.push_back(value);
        }
      }
    } else {
      for (std::int64_t e = 0; e < count; ++e) {
        field.tags.push_back(static_cast<std::uint64_t>(m_in.integer("data entry tag", 1, INT64_MAX)));
        for (std::size_t k = 0; k < components; ++k) field.values.push_back(m_in.finite_double("data value"));
      }
    }
    m_fields.push_back(std::move(field));
  }

  /// Stores the data sections that give a scalar or 3-vector for every node (every tet); others are skipped.
  void build_fields(TetMesh& mesh) {
    for (const RawField& raw : m_fields) {
      if (raw.components != 1 && raw.components != 3) continue;
      const std::size_t count = raw.on_nodes ? mesh.vertex_count() : mesh.tet_count();
      const auto components = static_cast<std::size_t>(raw.components);
      std::vector<double> values(count * components, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t e = 0; e < raw.tags.size(); ++e) {
        std::size_t index = 0;
        if (raw.on_nodes) {
          const auto it = m_node_index.find(raw.tags[e]);
          if (it == m_node_index.end()) {
            fail_at(raw.position, "$NodeData '" + raw.name + "' gives a value for node tag " +
                                      std::to_string(raw.tags[e]) + ", which $Nodes does not define");
          }
          index = static_cast<std::size_t>(it->second);
        } else {
          const auto it = std::lower_bound(m_tets.begin(), m_tets.end(), raw.tags[e],
                                           [](const RawTet& t, std::uint64_t tag) { return t.tag < tag; });
          if (it == m_tets.end() || it->tag != raw.tags[e]) continue;  // data on a skipped element type
          index = static_cast<std::size_t>(it - m_tets.begin());
        }
        for (std::size_t k = 0; k < components; ++k) values[index * components + k] = raw.values[e * components + k];
      }
      if (std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) continue;  // partial
      FieldSet& fields = raw.on_nodes ? mesh.vertex_fields : mesh.tet_fields;
      if (raw.components == 1) {
        fields.scalars[raw.name] = std::move(values);
      } else {
        std::vector<Vec3> vectors(count);
        for (std::size_t i = 0; i < count; ++i) vectors[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
        fields.vectors[raw.name] = std::move(vectors);
      }
    }
  }

  /// Fails at byte `position` of the file ("line N" in text files, "byte N" in binary ones).
  [[noreturn]] void fail_at(std::size_t position, const std::string& problem) {
    m_in.seek(position);
    m_binary ? m_in.fail_binary(problem) : m_in.fail(problem);
  }

  TetMesh build() {
    std::stable_sort(m_tets.begin(), m_tets.end(), [](const RawTet& a, const RawTet& b) { return a.tag < b.tag; });
    if (m_tets.size() > static_cast<std::size_t>(max_index)) m_in.fail("more than 2^31-1 tets");
    TetMesh mesh;
    mesh.positions = std::move(m_positions);
    mesh.tets.reserve(m_tets.size());
    mesh.tet_labels.reserve(m_tets.size());
    bool labelled = false;
    for (std::size_t i = 0; i < m_tets.size(); ++i) {
      const RawTet& raw = m_tets[i];
      if (i > 0 && raw.tag == m_tets[i - 1].tag)
        fail_at(raw.position, "element tag " + std::to_string(raw.tag) + " is used twice");
      Tet tet;
      for (int k = 0; k < 4; ++k) {
        const auto it = m_node_index.find(raw.nodes[k]);
        if (it == m_node_index.end()) {
          fail_at(raw.position, "element " + std::to_string(raw.tag) + " uses node tag " +
                                    std::to_string(raw.nodes[k]) + ", which $Nodes does not define");
        }
        tet[k] = it->second;
      }
      mesh.tets.push_back(tet);
      mesh.tet_labels.push_back(raw.label);
      labelled = labelled || raw.label != tissue_flesh;
    }
    if (!labelled) mesh.tet_labels.clear();
    build_fields(mesh);
    mesh.validate(m_in.source());
    return mesh;
  }

  TextCursor m_in;
  int m_version = 0;  // 0 (not seen yet), 2 or 4
  bool m_binary = false;
  bool m_have_nodes = false, m_have_elements = false;
  std::map<std::pair<int, int>, std::string> m_physical_names;  // (dimension, tag) -> name
  std::unordered_map<int, int> m_volume_physical;               // volume entity tag -> first physical tag
  std::vector<Vec3> m_positions;
  std::unordered_map<std::uint64_t, Index> m_node_index;  // node tag -> index
  std::vector<RawTet> m_tets;                             // sorted by tag in build()
  std::vector<RawField> m_fields;
};

// ---- writing
template <class T>
void append_binary(std::string& out, T value);

/// One $NodeData/$ElementData view per field (time 0, step 0); entity tags are index + 1 as written above.
void append_field_data(std::string& out, const FieldSet& fields, bool on_nodes, bool binary) {
  const char* section = on_nodes ? "NodeData" : "ElementData";
  auto write = [&](const std::string& name, std::size_t count, int components, auto value_at) {
    std::string quoted_name = name;
    std::replace(quoted_name.begin(), quoted_name.end(), '"', '\'');  // names are double-quoted in the file
    out += std::string("$") + section + "\n1\n\"" + quoted_name + "\"\n1\n0\n3\n0\n" + std::to_string(components) +
           "\n" + std::to_string(count) + "\n";
    for (std::size_t i = 0; i < count; ++i) {
      if (binary) {
        append_binary<std::int32_t>(out, static_cast<std::int32_t>(i + 1));
        for (int k = 0; k < components; ++k) append_binary<double>(out, value_at(i, k));
      } else {
        append_integer(out, static_cast<std::int64_t>(i) + 1);
        for (int k = 0; k < components; ++k) {
          out += ' ';
          append_double(out, value_at(i, k));
        }
        out += '\n';
      }
    }
    out += binary ? "\n$End" : "$End";
    out += std::string(section) + "\n";
  };
  for (const auto& [name, values] : fields.scalars) {
    write(name, values.size(), 1, [&v = values](std::size_t i, int) { return v[i]; });
  }
  for (const auto& [name, values] : fields.vectors) {
    write(name, values.size(), 3, [&v = values](std::size_t i, int k) { return v[i][k]; });
  }
}

template <class T>
void append_binary(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

TetMesh read_gmsh(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  return parse_gmsh(bytes, path.string());
}

TetMesh parse_gmsh(std::string_view bytes, const std::string& source) {
  return GmshReader(bytes, source).read();
}

void write_gmsh(const std::filesystem::path& path, const TetMesh& mesh, bool binary) {
  mesh.validate("mesh written to " + path.string());
  const std::size_t tet_count = mesh.tet_count();
  const std::size_t node_count = mesh.vertex_count();

  // One volume entity (tags 1..K) and physical group (tags 1..K) per distinct label, in label order.
  std::vector<int> labels;
  for (std::size_t t = 0; t < tet_count; ++t) labels.push_back(mesh.label(t));
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  if (labels.empty() && node_count > 0) labels.push_back(tissue_flesh);  // nodes need a volume entity
  std::map<int, int> entity_of_label;
  for (std::size_t k = 0; k < labels.size(); ++k) entity_of_label[labels[k]] = static_cast<int>(k + 1);
  std::vector<std::vector<std::size_t>> tets_of_entity(labels.size());
  for (std::size_t t = 0; t < tet_count; ++t) tets_of_entity[entity_of_label[mesh.label(t)] - 1].push_back(t);
  std::size_t element_blocks = 0;
  for (const auto& block : tets_of_entity) element_blocks += block.empty() ? 0 : 1;

  std::string out;
  out.reserve(binary ? 64 + node_count * 32 + tet_count * 40 : 64 + node_count * 60 + tet_count * 48);
  out += binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n";
  if (binary) {
    append_binary<std::int32_t>(out, 1);
    out += "\n";
  }
  out += "$EndMeshFormat\n$PhysicalNames\n" + std::to_string(labels.size()) + "\n";
  for (std::size_t k = 0; k < labels.size(); ++k) {
    out += "3 " + std::to_string(k + 1) + " \"" + name_of_label(labels[k]) + "\"\n";
  }
  out += "$EndPhysicalNames\n$Entities\n";
  if (binary) {
    for (std::uint64_t c : {std::uint64_t{0}, std::uint64_t{0}, std::uint64_t{0}, std::uint64_t{labels.size()}}) {
      append_binary(out, c);
    }
  } else {
    out += "0 0 0 " + std::to_string(labels.size()) + "\n";
  }
  for (std::size_t k = 0; k < labels.size(); ++k) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (std::size_t t : tets_of_entity[k]) {
      for (Index v : mesh.tets[t]) {
        lo = lo.cwiseMin(mesh.positions[v]);
        hi = hi.cwiseMax(mesh.positions[v]);
      }
    }
    if (tets_of_entity[k].empty()) {  // the entity that only holds the nodes of a mesh without tets
      for (const Vec3& p : mesh.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    const int tag = static_cast<int>(k + 1);
    if (binary) {
      append_binary<std::int32_t>(out, tag);
      for (int i = 0; i < 3; ++i) append_binary(out, lo[i]);
      for (int i = 0; i < 3; ++i) append_binary(out, hi[i]);
      append_binary<std::uint64_t>(out, 1);
      append_binary<std::int32_t>(out, tag);
      append_binary<std::uint64_t>(out, 0);
    } else {
      out += std::to_string(tag);
      for (const Vec3* corner : {&lo, &hi}) {
        for (int i = 0; i < 3; ++i) {
          out += ' ';
          append_double(out, (*corner)[i]);
        }
      }
      out += " 1 " + std::to_string(tag) + " 0\n";
    }
  }
  out += binary ? "\n$EndEntities\n$Nodes\n" : "$EndEntities\n$Nodes\n";

  // All nodes in one block of volume entity 1 (Gmsh requires an entity; the first volume is as good as any).
  const std::uint64_t node_blocks = node_count > 0 ? 1 : 0;
  const std::uint64_t node_entity = 1;
  if (binary) {
    append_binary(out, node_blocks);
    append_binary<std::uint64_t>(out, node_count);
    append_binary<std::uint64_t>(out, node_count > 0 ? 1 : 0);
    append_binary<std::uint64_t>(out, node_count);
    if (node_blocks) {
      append_binary<std::int32_t>(out, 3);
      append_binary<std::int32_t>(out, static_cast<std::int32_t>(node_entity));
      append_binary<std::int32_t>(out, 0);
      append_binary<std::uint64_t>(out, node_count);
      for (std::uint64_t v = 0; v < node_count; ++v) append_binary(out, v + 1);
      for (const Vec3& p : mesh.positions) {
        for (int i = 0; i < 3; ++i) append_binary(out, p[i]);
      }
    }
    out += "\n$EndNodes\n$Elements\n";
  } else {
    out += std::to_string(node_blocks) + " " + std::to_string(node_count) + " " + (node_count > 0 ? "1 " : "0 ") +
           std::to_string(node_count) + "\n";
    if (node_blocks) {
      out += "3 " + std::to_string(node_entity) + " 0 " + std::to_string(node_count) + "\n";
      for (std::size_t v = 0; v < node_count; ++v) {
        append_integer(out, static_cast<std::int64_t>(v) + 1);
        out += '\n';
      }
      for (const Vec3& p : mesh.positions) {
        append_double(out, p.x());
        out += ' ';
        append_double(out, p.y());
        out += ' ';
        append_double(out, p.z());
        out += '\n';
      }
    }
    out += "$EndNodes\n$Elements\n";
  }

  // One element block per label; element tags keep the tet order (t + 1).
  if (binary) {
    append_binary<std::uint64_t>(out, element_blocks);
    append_binary<std::uint64_t>(out, tet_count);
    append_binary<std::uint64_t>(out, tet_count > 0 ? 1 : 0);
    append_binary<std::uint64_t>(out, tet_count);
  } else {
    out += std::to_string(element_blocks) + " " + std::to_string(tet_count) + " " + (tet_count > 0 ? "1 " : "0 ") +
           std::to_string(tet_count) + "\n";
  }
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const auto& block = tets_of_entity[k];
    if (block.empty()) continue;
    if (binary) {
      append_binary<std::int32_t>(out, 3);
      append_binary<std::int32_t>(out, static_cast<std::int32_t>(k + 1));
      append_binary<std::int32_t>(out, gmsh_tet4);
      append_binary<std::uint64_t>(out, block.size());
      for (std::size_t t : block) {
        append_binary<std::uint64_t>(out, t + 1);
        for (Index v : mesh.tets[t]) append_binary<std::uint64_t>(out, static_cast<std::uint64_t>(v) + 1);
      }
    } else {
      out += "3 " + std::to_string(k + 1) + " 4 " + std::to_string(block.size()) + "\n";
      for (std::size_t t : block) {
        append_integer(out, static_cast<std::int64_t>(t) + 1);
        for (Index v : mesh.tets[t]) {
          out += ' ';
          append_integer(out, std::int64_t{v} + 1);
        }
        out += '\n';
      }
    }
  }
  out += binary ? "\n$EndElements\n" : "$EndElements\n";
  append_field_data(out, mesh.vertex_fields, true, binary);
  append_field_data(out, mesh.tet_fields, false, binary);
  write_file_atomic(path, out);
}

}  // namespace forensim
