#pragma once
/// Bounds-checked reading position in a whole file held in memory, shared by the tet_io readers (Gmsh,
/// TetGen). Every failure throws InputError naming the file and "line N" (text) or "byte N" (binary), so a
/// hostile or truncated file can never read past the end or crash.

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace forensim {

class TextCursor {
 public:
  /// `bytes` must outlive the cursor; `source` names the file in error messages.
  TextCursor(std::string_view bytes, std::string source);

  const std::string& source() const { return m_source; }
  std::string_view bytes() const { return m_bytes; }
  std::size_t position() const { return m_pos; }
  std::size_t remaining() const { return m_bytes.size() - m_pos; }
  bool at_end() const { return m_pos >= m_bytes.size(); }
  /// Moves to absolute byte `position` (clamped to the end).
  void seek(std::size_t position);

  /// "line N" (1-based) of the current position.
  std::string line_location() const;
  /// "byte N" (0-based) of the current position.
  std::string byte_location() const;
  /// Throws InputError(source, line_location(), problem).
  [[noreturn]] void fail(const std::string& problem) const;
  /// Throws InputError(source, byte_location(), problem).
  [[noreturn]] void fail_binary(const std::string& problem) const;

  /// Skips spaces, tabs and line breaks.
  void skip_whitespace();
  /// Skips spaces and tabs only (stays on the current line).
  void skip_blanks();
  /// True when only spaces/tabs remain before the end of the current line (or file).
  bool at_line_end();
  /// Next whitespace-separated token; fails naming `what` at the end of the file.
  std::string_view token(const char* what);
  /// Next token on the current line, or an empty view when the line has no more tokens.
  std::string_view token_on_line();
  /// Rest of the current line without its line break (\n or \r\n); moves past the break.
  std::string_view line();

  /// Next token as a signed integer in [min, max]; fails naming `what` otherwise.
  std::int64_t integer(const char* what, std::int64_t min = INT64_MIN, std::int64_t max = INT64_MAX);
  /// Next token as a finite double; fails naming `what` for NaN, infinity or a malformed number.
  double finite_double(const char* what);

  /// Consumes exactly `n` raw bytes; fails (binary location) when fewer remain.
  std::string_view raw(std::size_t n, const char* what);
  /// Reads one native-endian value of trivially copyable type T from raw bytes.
  template <class T>
  T binary(const char* what) {
    T value;
    std::memcpy(&value, raw(sizeof(T), what).data(), sizeof(T));
    return value;
  }

 private:
  std::string_view m_bytes;
  std::string m_source;
  std::size_t m_pos = 0;
};

/// Parses a whole token as an integer; false when it is not one or does not fit.
bool parse_integer(std::string_view token, std::int64_t& value);
/// Parses a whole token as a double (finite or not); false when malformed.
bool parse_double(std::string_view token, double& value);

}  // namespace forensim
