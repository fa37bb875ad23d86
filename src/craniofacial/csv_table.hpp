#pragma once
/// Comma-separated tables as the craniofacial files use them (tissue-depth tables, landmark lists): RFC 4180
/// fields (double quotes around fields that hold commas, "" for a quote inside them), a header row naming the
/// columns, and '#' comment lines before the header that carry the table's source. Parsing is strict so that a
/// malformed file is reported with its line and column name instead of being read half right.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace forensim {

/// One data row: its fields, in header order, and the 1-based line it starts on.
struct CsvRow {
  std::vector<std::string> fields;
  int line = 0;
};

/// A parsed table.
struct CsvTable {
  std::string source;                 ///< file path or description, for messages
  std::vector<std::string> comments;  ///< '#' lines before the header, without the '#' and leading space
  std::vector<std::string> columns;   ///< header names, trimmed, lower case
  std::vector<CsvRow> rows;           ///< data rows (blank lines and later '#' lines are skipped)
  int header_line = 0;                ///< 1-based line of the header

  /// Index of column `name`, or nullopt.
  std::optional<std::size_t> column(std::string_view name) const;
};

/// Parses CSV text. Every row must have as many fields as the header. Throws InputError(source, "line N",
/// problem) for an unterminated quote, a stray quote inside an unquoted field, a wrong field count, a NUL
/// byte, an empty or duplicate header name, or a file with no header.
CsvTable parse_csv(std::string_view text, const std::string& source);

/// Checks the header against the columns a format knows: every name in `required` must be present; a name
/// in neither `required` nor `optional` is an error with the nearest known name ("did you mean"). Throws
/// InputError(table.source, "line H", ...).
void check_csv_columns(const CsvTable& table, const std::vector<std::string>& required,
                       const std::vector<std::string>& optional);

/// Parses a finite decimal number from a whole field (surrounding spaces allowed). Throws InputError naming
/// source, "line N, field <column>" and the text when it is empty, not a number, NaN or infinite.
double parse_csv_number(const std::string& text, const std::string& source, int line, const std::string& column);

/// Quotes a field for writing when it holds a comma, quote, '#' at its start, or a line break.
std::string csv_field(const std::string& text);

}  // namespace forensim
