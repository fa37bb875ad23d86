#include <gtest/gtest.h>

#include "core/error.hpp"
#include "craniofacial/csv_table.hpp"

using namespace forensim;

TEST(CsvTable, QuotedFieldsCommentsAndBlankLines) {
  const CsvTable t = parse_csv(
      "# source: somewhere, 2024\n\n Name , Value\n\"a, b\",\"say \"\"hi\"\"\"\n  c ,  2 \n# later "
      "comment\n\"multi\nline\",3\r\n",
      "t.csv");
  ASSERT_EQ(t.comments.size(), 1u);
  EXPECT_EQ(t.comments[0], "source: somewhere, 2024");
  ASSERT_EQ(t.columns.size(), 2u);
  EXPECT_EQ(t.columns[0], "name");
  EXPECT_EQ(t.header_line, 3);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0].fields[0], "a, b");
  EXPECT_EQ(t.rows[0].fields[1], "say \"hi\"");
  EXPECT_EQ(t.rows[1].fields[0], "c");
  EXPECT_EQ(t.rows[1].line, 5);
  EXPECT_EQ(t.rows[2].fields[0], "multi\nline");
  EXPECT_EQ(t.rows[2].line, 7);
}

TEST(CsvTable, FieldRoundTripThroughQuoting) {
  for (const std::string s : {"plain", "a,b", "q\"uote", "#hash", "line\nbreak", " padded "}) {
    const CsvTable t = parse_csv("x\n" + csv_field(s) + "\n", "t");
    ASSERT_EQ(t.rows.size(), 1u) << s;
    EXPECT_EQ(t.rows[0].fields[0], s);
  }
}

TEST(CsvTable, MalformedTablesNameTheLine) {
  const auto message = [](const std::string& text) {
    try {
      parse_csv(text, "bad.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("a,b\n1,2,3\n").find("bad.csv:line 2"), std::string::npos);
  EXPECT_NE(message("a,b\n\"open,2\n").find("unterminated"), std::string::npos);
  EXPECT_NE(message("a,b\nx\"y,2\n").find("quote"), std::string::npos);
  EXPECT_NE(message("a,a\n").find("twice"), std::string::npos);
  EXPECT_NE(message("# only a comment\n").find("no header"), std::string::npos);
  EXPECT_NE(message(std::string("a\nx\0y\n", 6)).find("NUL"), std::string::npos);
}

TEST(CsvTable, NumbersMustBeFinite) {
  EXPECT_DOUBLE_EQ(parse_csv_number(" 2.5 ", "t", 1, "x"), 2.5);
  EXPECT_DOUBLE_EQ(parse_csv_number("-1e-3", "t", 1, "x"), -1e-3);
  for (const std::string bad : {"nan", "NaN", "inf", "-inf", "", "1.5mm", "1e999", "0x10"}) {
    EXPECT_THROW(parse_csv_number(bad, "t", 4, "mean_mm"), InputError) << bad;
  }
  try {
    parse_csv_number("nan", "t.csv", 4, "mean_mm");
  } catch (const InputError& e) {
    EXPECT_EQ(e.location(), "line 4, field mean_mm");
  }
}

TEST(CsvTable, UnknownColumnsSuggestKnownOnes) {
  const CsvTable t = parse_csv("landmark,mean_m\nn,6\n", "t.csv");
  try {
    check_csv_columns(t, {"landmark", "mean_mm"}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'mean_mm'"), std::string::npos) << e.what();
  }
  const CsvTable u = parse_csv("landmark\nn\n", "t.csv");
  EXPECT_THROW(check_csv_columns(u, {"landmark", "mean_mm"}, {}), InputError);
}
