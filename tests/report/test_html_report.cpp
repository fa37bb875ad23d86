#include <gtest/gtest.h>

#include "core/atomic_file.hpp"
#include "core/base64.hpp"
#include "report/html_report.hpp"
#include "support/test_support.hpp"

using namespace forensim;

TEST(HtmlReport, EscapesTextAndEmbedsPictures) {
  HtmlReport report("Run <1>");
  report.section("Wound & scab", "a < b");
  report.figure_png("PNGDATA", "caption \"x\"");
  report.table({"stage", "s"}, {{"iso<surface", "1.5"}});
  const std::string html = report.html();
  EXPECT_NE(html.find("Run &lt;1&gt;"), std::string::npos);
  EXPECT_NE(html.find("Wound &amp; scab"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64," + base64_encode("PNGDATA")), std::string::npos);
  EXPECT_NE(html.find("caption &quot;x&quot;"), std::string::npos);
  EXPECT_NE(html.find("iso&lt;surface"), std::string::npos);
  EXPECT_EQ(html.find("<1>"), std::string::npos);
}

TEST(HtmlReport, WritesAtomically) {
  const auto dir = test::scratch_dir("report");
  HtmlReport report("t");
  report.paragraph("hello");
  report.write(dir / "report.html");
  EXPECT_NE(read_file(dir / "report.html").find("<p>hello</p>"), std::string::npos);
}
