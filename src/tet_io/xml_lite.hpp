#pragma once
/// A small, hostile-input-safe XML reader and escaper for VTK XML files (.vtu, .pvd). forensim's Debian
/// dependency set has no XML library, and VTK files need only elements, attributes, character data,
/// comments and the raw <AppendedData> block (which is not XML at all and stops the parse, as in VTK).
/// Nesting depth is limited so a hostile file cannot exhaust the stack.

#include <optional>
#include <string>
#include <string_view>

#include <utility>
#include <vector>
#include "core/xml_escape.hpp"

namespace forensim {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;  ///< in file order, entities decoded
  std::string text;                                             ///< character data directly inside, decoded
  std::vector<XmlElement> children;
  std::size_t line = 0;  ///< 1-based line of the start tag

  /// Value of attribute `key`, or nullptr.
  const std::string* attribute(std::string_view key) const;
  /// First child named `child_name`, or nullptr.
  const XmlElement* child(std::string_view child_name) const;
  /// "line N" of the start tag, for error locations.
  std::string location() const { return "line " + std::to_string(line); }
};

struct XmlDocument {
  XmlElement root;
  /// Byte range of the appended data (the bytes after '_' up to "</AppendedData>"), when the file has
  /// an <AppendedData> block; the element itself is in the tree, without children.
  std::optional<std::pair<std::size_t, std::size_t>> appended;
};

/// Parses `bytes`; throws InputError(source, "line N", problem) for malformed XML, mismatched tags,
/// nesting deeper than 64, or a missing root element.
XmlDocument parse_xml(std::string_view bytes, const std::string& source);

}  // namespace forensim
