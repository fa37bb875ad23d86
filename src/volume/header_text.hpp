#pragma once
/// Small text helpers shared by the NRRD and MetaImage header parsers: reading a header from the start of a file
/// without reading its data, splitting lines and parsing numbers with the field and line named on error.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace forensim {

/// A header value with the 1-based line it was read from, for error locations.
struct HeaderField {
  std::string value;
  int line = 0;
  std::string location() const { return "line " + std::to_string(line); }
};

/// One header line: its text (trailing CR removed) and 1-based line number.
struct HeaderLine {
  std::string text;
  int number = 0;
};

/// The header part of a file: lines up to the first empty line (or the end of the file), and the byte offset
/// just after that empty line (the start of attached data; the file size when there is none).
struct HeaderText {
  std::vector<HeaderLine> lines;
  std::uint64_t data_offset = 0;
  bool ended_by_blank_line = false;
};

/// Reads the header of `file`, at most `max_header_bytes` long; `stop_at_blank_line` ends it at the first empty
/// line (NRRD). `stop_prefix` (when not empty) ends it after the first line starting with that text (MetaImage's
/// "ElementDataFile"). Throws IoError when unreadable, InputError when the header is longer than the limit or
/// holds NUL bytes.
HeaderText read_header_text(const std::filesystem::path& file, bool stop_at_blank_line, std::string_view stop_prefix,
                            std::uint64_t max_header_bytes = std::uint64_t{16} << 20);

/// Whitespace-trimmed copy.
std::string trim(std::string_view s);
/// Splits on whitespace (and, with `commas`, on commas and parentheses too).
std::vector<std::string> split_words(std::string_view s, bool commas = false);
/// Lower-case copy (ASCII).
std::string to_lower(std::string_view s);

/// Parses a decimal number (NaN and inf are parsed as such; callers check finiteness). Throws
/// InputError(source, location, "<what> '<text>' is not a number").
double parse_double(const std::string& text, const std::string& source, const std::string& location,
                    const std::string& what);
/// Parses a 64-bit signed integer; throws InputError as parse_double.
std::int64_t parse_int(const std::string& text, const std::string& source, const std::string& location,
                       const std::string& what);

}  // namespace forensim
