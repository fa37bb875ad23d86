#include "volume/header_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/error.hpp"

namespace forensim {

HeaderText read_header_text(const std::filesystem::path& file, bool stop_at_blank_line, std::string_view stop_prefix,
                            std::uint64_t max_header_bytes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw IoError(file.string(), "file does not exist");
    throw IoError(file.string(), "cannot open for reading");
  }
  HeaderText header;
  std::string line;
  std::uint64_t consumed = 0;
  int number = 0;
  while (true) {
    line.clear();
    char c = 0;
    bool got_newline = false;
    while (in.get(c)) {
      ++consumed;
      if (c == '\n') {
        got_newline = true;
        break;
      }
      if (c == '\0') {
        throw InputError(file.string(), "line " + std::to_string(number + 1), "header holds a NUL byte (binary data?)");
      }
      line += c;
      if (consumed > max_header_bytes) {
        throw InputError(file.string(), "line " + std::to_string(number + 1),
                         "header is longer than " + std::to_string(max_header_bytes) + " bytes");
      }
    }
    if (!got_newline && line.empty()) break;  // end of file
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (stop_at_blank_line && line.empty()) {
      header.ended_by_blank_line = true;
      break;
    }
    const bool last = !stop_prefix.empty() && trim(line).rfind(stop_prefix, 0) == 0;
    header.lines.push_back({line, number});
    if (last || !got_newline) break;
  }
  if (in.bad()) throw IoError(file.string(), "read failed");
  header.data_offset = consumed;
  return header;
}

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::vector<std::string> split_words(std::string_view s, bool commas) {
  std::vector<std::string> words;
  std::string cur;
  for (char c : s) {
    const bool sep = std::isspace(static_cast<unsigned char>(c)) || (commas && (c == ',' || c == '(' || c == ')'));
    if (sep) {
      if (!cur.empty()) words.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) words.push_back(cur);
  return words;
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

double parse_double(const std::string& text, const std::string& source, const std::string& location,
                    const std::string& what) {
  const std::string low = to_lower(text);
  if (low == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (low == "inf" || low == "+inf") return std::numeric_limits<double>::infinity();
  if (low == "-inf") return -std::numeric_limits<double>::infinity();
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || ptr != last || text.empty()) {
    throw InputError(source, location, what + " '" + text + "' is not a number");
  }
  return v;
}

std::int64_t parse_int(const std::string& text, const std::string& source, const std::string& location,
                       const std::string& what) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec == std::errc::result_out_of_range)
    throw InputError(source, location, what + " '" + text + "' is out of range");
  if (ec != std::errc() || ptr != last || text.empty()) {
    throw InputError(source, location, what + " '" + text + "' is not an integer");
  }
  return v;
}

}  // namespace forensim
