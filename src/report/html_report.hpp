#pragma once
/// A self-contained HTML report of a run: sections with text, pictures (PNG embedded as data URIs, so the
/// page opens anywhere with no other files), tables of figures and timings. `forensim demo` writes one that
/// shows every system; each system's run folder can write its own.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace forensim {

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  /// Starts a new section (h2) with an optional introductory paragraph (plain text, escaped).
  void section(const std::string& heading, const std::string& text = "");
  /// A paragraph of plain text (escaped).
  void paragraph(const std::string& text);
  /// A picture from encoded PNG bytes, with a caption. `width_px` 0 = natural size (capped by the page).
  void figure_png(const std::string& png_bytes, const std::string& caption, int width_px = 0);
  /// A picture read from a PNG file (its bytes are embedded). Throws IoError if it cannot be read.
  void figure_file(const std::filesystem::path& png_path, const std::string& caption, int width_px = 0);
  /// A table: header row and rows of cells (plain text, escaped).
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  /// A two-column table of (name, value) facts.
  void facts(const std::vector<std::pair<std::string, std::string>>& rows);
  /// A preformatted block (commands, logs).
  void code(const std::string& text);
  /// A note flagged as a problem (a stage that failed), shown prominently.
  void warning(const std::string& text);

  /// The page as HTML.
  std::string html() const;
  /// Writes the page atomically.
  void write(const std::filesystem::path& path) const;

 private:
  std::string m_title;
  std::string m_body;
};

/// Escapes &, <, >, " and ' for HTML text and attributes.
std::string html_escape(const std::string& text);

}  // namespace forensim
