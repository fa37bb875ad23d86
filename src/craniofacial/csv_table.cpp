#include "craniofacial/csv_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

#include "core/error.hpp"
#include "core/job.hpp"

namespace forensim {
namespace {

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(b, e - b));
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string line_location(int line) {
  return "line " + std::to_string(line);
}

/// Splits one record starting at `pos`; advances `pos` past its line break and `line` past its lines.
std::vector<std::string> read_record(std::string_view text, std::size_t& pos, int& line, const std::string& source) {
  std::vector<std::string> fields;
  std::string field;
  const int start_line = line;
  bool quoted = false;      // inside a quoted field
  bool was_quoted = false;  // the current field was quoted (only spaces may follow the closing quote)
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == '\0') throw InputError(source, line_location(line), "NUL byte in text");
    if (quoted) {
      if (c == '"') {
        if (pos + 1 < text.size() && text[pos + 1] == '"') {
          field += '"';
          pos += 2;
          continue;
        }
        quoted = false;
        ++pos;
        continue;
      }
      if (c == '\n') ++line;
      field += c;
      ++pos;
      continue;
    }
    if (c == ',') {
      fields.push_back(was_quoted ? field : trim(field));
      field.clear();
      was_quoted = false;
      ++pos;
      continue;
    }
    if (c == '\n' || c == '\r') {
      pos += (c == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ? 2 : 1;
      ++line;
      fields.push_back(was_quoted ? field : trim(field));
      return fields;
    }
    if (c == '"') {
      if (!trim(field).empty() || was_quoted) {
        throw InputError(source, line_location(line),
                         "quote inside an unquoted field (field " + std::to_string(fields.size() + 1) +
                             "); quote the whole field and double inner quotes");
      }
      field.clear();
      quoted = true;
      was_quoted = true;
      ++pos;
      continue;
    }
    if (was_quoted && c != ' ' && c != '\t') {
      throw InputError(source, line_location(line),
                       "text after the closing quote of field " + std::to_string(fields.size() + 1));
    }
    if (!was_quoted) field += c;
    ++pos;
  }
  if (quoted) throw InputError(source, line_location(start_line), "unterminated quoted field");
  fields.push_back(was_quoted ? field : trim(field));
  return fields;
}

bool blank(std::string_view text, std::size_t pos) {
  while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
  return pos >= text.size() || text[pos] == '\n' || text[pos] == '\r';
}

void skip_line(std::string_view text, std::size_t& pos, int& line) {
  while (pos < text.size() && text[pos] != '\n') ++pos;
  if (pos < text.size()) ++pos;
  ++line;
}

}  // namespace

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i;
  }
  return std::nullopt;
}

CsvTable parse_csv(std::string_view text, const std::string& source) {
  CsvTable table;
  table.source = source;
  std::size_t pos = 0;
  int line = 1;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // UTF-8 byte order mark
  while (pos < text.size()) {
    std::size_t p = pos;
    while (p < text.size() && (text[p] == ' ' || text[p] == '\t')) ++p;
    if (p < text.size() && text[p] == '#') {
      std::size_t end = text.find('\n', p);
      if (end == std::string_view::npos) end = text.size();
      std::string comment = std::string(text.substr(p + 1, end - p - 1));
      if (!comment.empty() && comment.back() == '\r') comment.pop_back();
      if (comment.find('\0') != std::string::npos) throw InputError(source, line_location(line), "NUL byte in text");
      if (table.columns.empty()) table.comments.push_back(trim(comment));
      skip_line(text, pos, line);
      continue;
    }
    if (blank(text, pos)) {
      skip_line(text, pos, line);
      continue;
    }
    const int record_line = line;
    std::vector<std::string> fields = read_record(text, pos, line, source);
    if (table.columns.empty()) {
      table.header_line = record_line;
      std::set<std::string> seen;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        std::string name = lower(trim(fields[i]));
        if (name.empty()) {
          throw InputError(source, line_location(record_line),
                           "header column " + std::to_string(i + 1) + " has no name");
        }
        if (!seen.insert(name).second) {
          throw InputError(source, line_location(record_line), "header names column '" + name + "' twice");
        }
        table.columns.push_back(std::move(name));
      }
      continue;
    }
    if (fields.size() != table.columns.size()) {
      throw InputError(
          source, line_location(record_line),
          "has " + std::to_string(fields.size()) + " fields, the header has " + std::to_string(table.columns.size()));
    }
    table.rows.push_back({std::move(fields), record_line});
  }
  if (table.columns.empty()) throw InputError(source, "", "no header row (the table is empty)");
  return table;
}

void check_csv_columns(const CsvTable& table, const std::vector<std::string>& required,
                       const std::vector<std::string>& optional) {
  const std::string location = line_location(table.header_line);
  for (const std::string& name : table.columns) {
    const bool known = std::find(required.begin(), required.end(), name) != required.end() ||
                       std::find(optional.begin(), optional.end(), name) != optional.end();
    if (known) continue;
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(3, name.size() / 2) + 1;
    for (const auto* list : {&required, &optional}) {
      for (const std::string& candidate : *list) {
        const std::size_t d = edit_distance(name, candidate);
        if (d < best_distance) {
          best_distance = d;
          best = candidate;
        }
      }
    }
    std::string problem = "unknown column '" + name + "'";
    if (!best.empty()) problem += " (did you mean '" + best + "'?)";
    throw InputError(table.source, location, problem);
  }
  for (const std::string& name : required) {
    if (!table.column(name)) throw InputError(table.source, location, "missing required column '" + name + "'");
  }
}

double parse_csv_number(const std::string& text, const std::string& source, int line, const std::string& column) {
  const std::string location = line_location(line) + ", field " + column;
  const std::string t = trim(text);
  if (t.empty()) throw InputError(source, location, "empty, a number is required");
  double value = 0.0;
  const char* begin = t.data();
  const char* end = t.data() + t.size();
  if (*begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end) throw InputError(source, location, "'" + t + "' is not a number");
  if (!std::isfinite(value)) throw InputError(source, location, "'" + t + "' is not a finite number");
  return value;
}

std::string csv_field(const std::string& text) {
  const bool needs_quotes = text.find_first_of(",\"\r\n") != std::string::npos ||
                            (!text.empty() && (text.front() == '#' || text.front() == ' ' || text.back() == ' '));
  if (!needs_quotes) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace forensim
