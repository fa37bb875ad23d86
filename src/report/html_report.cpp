#include "report/html_report.hpp"

#include <ctime>

#include "core/atomic_file.hpp"
#include "core/base64.hpp"
#include "core/run_folder.hpp"
#include "core/xml_escape.hpp"

namespace forensim {

std::string html_escape(const std::string& text) {
  return xml_escape(text);
}

HtmlReport::HtmlReport(std::string title) : m_title(std::move(title)) {}

void HtmlReport::section(const std::string& heading, const std::string& text) {
  m_body += "<h2>" + html_escape(heading) + "</h2>\n";
  if (!text.empty()) paragraph(text);
}

void HtmlReport::paragraph(const std::string& text) {
  m_body += "<p>" + html_escape(text) + "</p>\n";
}

void HtmlReport::figure_png(const std::string& png_bytes, const std::string& caption, int width_px) {
  m_body += "<figure><img alt=\"" + html_escape(caption) + "\"";
  if (width_px > 0) m_body += " width=\"" + std::to_string(width_px) + "\"";
  m_body += " src=\"data:image/png;base64," + base64_encode(png_bytes) + "\"><figcaption>" + html_escape(caption) +
            "</figcaption></figure>\n";
}

void HtmlReport::figure_file(const std::filesystem::path& png_path, const std::string& caption, int width_px) {
  figure_png(read_file(png_path, std::size_t{256} << 20), caption, width_px);
}

void HtmlReport::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  m_body += "<table><thead><tr>";
  for (const auto& h : header) m_body += "<th>" + html_escape(h) + "</th>";
  m_body += "</tr></thead><tbody>\n";
  for (const auto& row : rows) {
    m_body += "<tr>";
    for (const auto& cell : row) m_body += "<td>" + html_escape(cell) + "</td>";
    m_body += "</tr>\n";
  }
  m_body += "</tbody></table>\n";
}

void HtmlReport::facts(const std::vector<std::pair<std::string, std::string>>& rows) {
  m_body += "<table class=\"facts\"><tbody>\n";
  for (const auto& [name, value] : rows) {
    m_body += "<tr><th>" + html_escape(name) + "</th><td>" + html_escape(value) + "</td></tr>\n";
  }
  m_body += "</tbody></table>\n";
}

void HtmlReport::code(const std::string& text) {
  m_body += "<pre>" + html_escape(text) + "</pre>\n";
}

void HtmlReport::warning(const std::string& text) {
  m_body += "<p class=\"warning\">" + html_escape(text) + "</p>\n";
}

std::string HtmlReport::html() const {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
                     html_escape(m_title) +
                     "</title>\n<style>\n"
                     "body{font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;"
                     "color:#222;background:#fafafa}\n"
                     "h1{border-bottom:2px solid #833;padding-bottom:.3em}h2{margin-top:2em;color:#633}\n"
                     "figure{display:inline-block;margin:.5em;vertical-align:top;max-width:100%}\n"
                     "figure img{max-width:100%;border:1px solid #ccc;background:#fff}\n"
                     "figcaption{font-size:.9em;color:#555;max-width:600px}\n"
                     "table{border-collapse:collapse;margin:.8em 0}td,th{border:1px solid #ccc;padding:.25em .6em;"
                     "text-align:left}th{background:#eee}\n"
                     "pre{background:#f0f0f0;padding:.6em;overflow-x:auto}\n"
                     ".warning{background:#fee;border-left:4px solid #c33;padding:.5em}\n"
                     "footer{margin-top:3em;color:#888;font-size:.85em}\n"
                     "</style></head><body>\n<h1>" +
                     html_escape(m_title) + "</h1>\n";
  page += m_body;
  page += "<footer>forensim " + html_escape(version_string()) + " &middot; generated " + stamp + "</footer>\n";
  page += "</body></html>\n";
  return page;
}

void HtmlReport::write(const std::filesystem::path& path) const {
  write_file_atomic(path, html());
}

}  // namespace forensim
