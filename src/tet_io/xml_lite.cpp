#include "tet_io/xml_lite.hpp"

#include <algorithm>
#include <cstdint>

#include "core/error.hpp"

namespace forensim {
namespace {

constexpr int max_depth = 64;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':' ||
         c == '-' || c == '.';
}

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

class XmlParser {
 public:
  XmlParser(std::string_view bytes, const std::string& source) : m_bytes(bytes), m_source(source) {}

  XmlDocument parse() {
    XmlDocument doc;
    skip_misc();
    if (at_end() || m_bytes[m_pos] != '<') fail("no root element");
    m_document = &doc;
    doc.root = element(0);
    if (!m_stopped) {
      skip_misc();
      if (!at_end()) fail("content after the root element");
    }
    return doc;
  }

 private:
  bool at_end() const { return m_pos >= m_bytes.size(); }
  bool starts_with(std::string_view s) const { return m_bytes.substr(m_pos, s.size()) == s; }

  std::size_t line() {
    m_line += static_cast<std::size_t>(std::count(m_bytes.begin() + static_cast<std::ptrdiff_t>(m_counted),
                                                  m_bytes.begin() + static_cast<std::ptrdiff_t>(m_pos), '\n'));
    m_counted = m_pos;
    return m_line;
  }

  [[noreturn]] void fail(const std::string& problem) {
    m_pos = std::min(m_pos, m_bytes.size());
    throw InputError(m_source, "line " + std::to_string(line()), problem);
  }

  void skip_spaces() {
    while (!at_end() && is_space(m_bytes[m_pos])) ++m_pos;
  }

  void skip_past(std::string_view terminator, const char* what) {
    const std::size_t at = m_bytes.find(terminator, m_pos);
    if (at == std::string_view::npos) fail(std::string("unterminated ") + what);
    m_pos = at + terminator.size();
  }

  /// Skips whitespace, comments, processing instructions and DOCTYPE outside the root element.
  void skip_misc() {
    while (true) {
      skip_spaces();
      if (starts_with("\xEF\xBB\xBF")) {
        m_pos += 3;
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (starts_with("<!--")) {
        skip_past("-->", "comment");
      } else if (starts_with("<!DOCTYPE")) {
        skip_past(">", "DOCTYPE");
      } else {
        return;
      }
    }
  }

  std::string name() {
    const std::size_t start = m_pos;
    while (!at_end() && is_name_char(m_bytes[m_pos])) ++m_pos;
    if (m_pos == start) fail("expected a name");
    return std::string(m_bytes.substr(start, m_pos - start));
  }

  /// Decodes character data or an attribute value up to (not including) `stop`.
  void decode(std::string_view raw, std::string& out) {
    out.reserve(out.size() + raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semicolon = raw.find(';', i);
      if (semicolon == std::string_view::npos || semicolon - i > 12) fail("unterminated entity reference");
      const std::string_view entity = raw.substr(i + 1, semicolon - i - 1);
      if (entity == "lt") {
        out += '<';
      } else if (entity == "gt") {
        out += '>';
      } else if (entity == "amp") {
        out += '&';
      } else if (entity == "quot") {
        out += '"';
      } else if (entity == "apos") {
        out += '\'';
      } else if (entity.size() > 1 && entity[0] == '#') {
        const bool hex = entity[1] == 'x';
        std::uint32_t code = 0;
        const std::string_view digits = entity.substr(hex ? 2 : 1);
        if (digits.empty()) fail("bad character reference");
        for (char c : digits) {
          int d = -1;
          if (c >= '0' && c <= '9') d = c - '0';
          if (hex && c >= 'a' && c <= 'f') d = c - 'a' + 10;
          if (hex && c >= 'A' && c <= 'F') d = c - 'A' + 10;
          if (d < 0) fail("bad character reference");
          code = code * (hex ? 16 : 10) + static_cast<std::uint32_t>(d);
          if (code > 0x10FFFF) fail("character reference out of range");
        }
        append_utf8(out, code);
      } else {
        fail("unknown entity '&" + std::string(entity) + ";'");
      }
      i = semicolon;
    }
  }

  XmlElement element(int depth) {
    if (depth > max_depth) fail("elements nested deeper than " + std::to_string(max_depth));
    XmlElement e;
    e.line = line();
    ++m_pos;  // '<'
    e.name = name();
    // Attributes.
    while (true) {
      const std::size_t before = m_pos;
      skip_spaces();
      if (at_end()) fail("unterminated start tag <" + e.name + ">");
      if (starts_with("/>")) {
        m_pos += 2;
        return e;
      }
      if (m_bytes[m_pos] == '>') {
        ++m_pos;
        break;
      }
      if (m_pos == before) fail("expected a space before an attribute in <" + e.name + ">");
      std::string key = name();
      skip_spaces();
      if (at_end() || m_bytes[m_pos] != '=') fail("attribute '" + key + "' has no value");
      ++m_pos;
      skip_spaces();
      if (at_end() || (m_bytes[m_pos] != '"' && m_bytes[m_pos] != '\'')) fail("attribute '" + key + "' is not quoted");
      const char quote = m_bytes[m_pos++];
      const std::size_t close = m_bytes.find(quote, m_pos);
      if (close == std::string_view::npos) fail("unterminated value of attribute '" + key + "'");
      const std::string_view raw = m_bytes.substr(m_pos, close - m_pos);
      if (raw.find('<') != std::string_view::npos) fail("'<' in the value of attribute '" + key + "'");
      for (const auto& attribute : e.attributes) {
        if (attribute.first == key) fail("attribute '" + key + "' repeated");
      }
      std::string value;
      decode(raw, value);
      e.attributes.emplace_back(std::move(key), std::move(value));
      m_pos = close + 1;
    }
    if (e.name == "AppendedData") {
      // Raw binary follows: not XML. It starts after '_' and runs to the last "</AppendedData>" (or the end).
      skip_spaces();
      if (at_end() || m_bytes[m_pos] != '_') fail("appended data does not start with '_'");
      const std::size_t begin = m_pos + 1;
      std::size_t end = m_bytes.rfind("</AppendedData>");
      if (end == std::string_view::npos || end < begin) end = m_bytes.size();
      m_document->appended = std::make_pair(begin, end);
      m_stopped = true;
      return e;
    }
    // Content.
    while (true) {
      const std::size_t next = m_bytes.find('<', m_pos);
      if (next == std::string_view::npos) {
        m_pos = m_bytes.size();
        fail("element <" + e.name + "> is not closed");
      }
      decode(m_bytes.substr(m_pos, next - m_pos), e.text);
      m_pos = next;
      if (starts_with("</")) {
        m_pos += 2;
        const std::string end_name = name();
        if (end_name != e.name) fail("</" + end_name + "> closes <" + e.name + ">");
        skip_spaces();
        if (at_end() || m_bytes[m_pos] != '>') fail("unterminated end tag </" + end_name + ">");
        ++m_pos;
        return e;
      }
      if (starts_with("<!--")) {
        skip_past("-->", "comment");
      } else if (starts_with("<![CDATA[")) {
        const std::size_t start = m_pos + 9;
        skip_past("]]>", "CDATA section");
        e.text.append(m_bytes.substr(start, m_pos - 3 - start));
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else {
        e.children.push_back(element(depth + 1));
        if (m_stopped) return e;
      }
    }
  }

  std::string_view m_bytes;
  const std::string& m_source;
  std::size_t m_pos = 0;
  std::size_t m_line = 1, m_counted = 0;
  bool m_stopped = false;
  XmlDocument* m_document = nullptr;
};

}  // namespace

const std::string* XmlElement::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return &v;
  }
  return nullptr;
}

const XmlElement* XmlElement::child(std::string_view child_name) const {
  for (const XmlElement& c : children) {
    if (c.name == child_name) return &c;
  }
  return nullptr;
}

XmlDocument parse_xml(std::string_view bytes, const std::string& source) {
  return XmlParser(bytes, source).parse();
}

}  // namespace forensim
