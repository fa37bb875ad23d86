#include "tet_io/text_cursor.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace forensim {
namespace {
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string quoted(std::string_view token) {
  constexpr std::size_t limit = 32;
  std::string out = "'";
  for (char c : token.substr(0, limit)) out += (c >= 32 && c < 127) ? c : '?';
  if (token.size() > limit) out += "...";
  return out + "'";
}
}  // namespace

bool parse_integer(std::string_view token, std::int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return !token.empty() && result.ec == std::errc() && result.ptr == end;
}

bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return !token.empty() && result.ec == std::errc() && result.ptr == end;
}

TextCursor::TextCursor(std::string_view bytes, std::string source) : m_bytes(bytes), m_source(std::move(source)) {}

void TextCursor::seek(std::size_t position) {
  m_pos = std::min(position, m_bytes.size());
}

std::string TextCursor::line_location() const {
  const std::size_t end = std::min(m_pos, m_bytes.size());
  const auto lines = std::count(m_bytes.begin(), m_bytes.begin() + static_cast<std::ptrdiff_t>(end), '\n');
  return "line " + std::to_string(lines + 1);
}

std::string TextCursor::byte_location() const {
  return "byte " + std::to_string(m_pos);
}

void TextCursor::fail(const std::string& problem) const {
  throw InputError(m_source, line_location(), problem);
}

void TextCursor::fail_binary(const std::string& problem) const {
  throw InputError(m_source, byte_location(), problem);
}

void TextCursor::skip_whitespace() {
  while (m_pos < m_bytes.size() && is_space(m_bytes[m_pos])) ++m_pos;
}

void TextCursor::skip_blanks() {
  while (m_pos < m_bytes.size() && is_blank(m_bytes[m_pos])) ++m_pos;
}

bool TextCursor::at_line_end() {
  skip_blanks();
  return m_pos >= m_bytes.size() || m_bytes[m_pos] == '\n';
}

std::string_view TextCursor::token(const char* what) {
  skip_whitespace();
  if (at_end()) fail(std::string("unexpected end of file while reading ") + what);
  const std::size_t start = m_pos;
  while (m_pos < m_bytes.size() && !is_space(m_bytes[m_pos])) ++m_pos;
  return m_bytes.substr(start, m_pos - start);
}

std::string_view TextCursor::token_on_line() {
  if (at_line_end()) return {};
  const std::size_t start = m_pos;
  while (m_pos < m_bytes.size() && !is_space(m_bytes[m_pos])) ++m_pos;
  return m_bytes.substr(start, m_pos - start);
}

std::string_view TextCursor::line() {
  const std::size_t start = m_pos;
  std::size_t end = m_bytes.find('\n', start);
  if (end == std::string_view::npos) end = m_bytes.size();
  m_pos = std::min(end + 1, m_bytes.size());
  std::string_view text = m_bytes.substr(start, end - start);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  return text;
}

std::int64_t TextCursor::integer(const char* what, std::int64_t min, std::int64_t max) {
  const std::size_t start = m_pos;
  const std::string_view t = token(what);
  std::int64_t value = 0;
  if (!parse_integer(t, value)) {
    m_pos = start;
    skip_whitespace();
    fail(std::string(what) + " is not an integer: " + quoted(t));
  }
  if (value < min || value > max) {
    m_pos = start;
    skip_whitespace();
    fail(std::string(what) + " " + std::to_string(value) + " is out of range [" + std::to_string(min) + ", " +
         std::to_string(max) + "]");
  }
  return value;
}

double TextCursor::finite_double(const char* what) {
  const std::size_t start = m_pos;
  const std::string_view t = token(what);
  double value = 0.0;
  if (!parse_double(t, value) || !std::isfinite(value)) {
    m_pos = start;
    skip_whitespace();
    fail(std::string(what) + " is not a finite number: " + quoted(t));
  }
  return value;
}

std::string_view TextCursor::raw(std::size_t n, const char* what) {
  if (n > remaining()) {
    fail_binary(std::string("truncated binary data: ") + what + " needs " + std::to_string(n) + " bytes, " +
                std::to_string(remaining()) + " remain");
  }
  const std::string_view out = m_bytes.substr(m_pos, n);
  m_pos += n;
  return out;
}

}  // namespace forensim
