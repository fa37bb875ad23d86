#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "core/error.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

// shared/reference/tissue-depth.md, section 1 (the 2023 T-Table): site -> (mean, SD) in mm.
const std::map<std::string, std::pair<double, double>> k_ttable = {
    {"op", {6, 2}},    {"v", {5, 1.5}},     {"g", {5.5, 1}},      {"n", {6, 1.5}},   {"mn", {4.5, 1.5}},
    {"rhi", {3, 1}},   {"ss", {13.5, 3.5}}, {"mp", {11.5, 2.5}},  {"pr", {12, 3}},   {"id", {13.5, 3}},
    {"sm", {11, 2}},   {"pg", {11, 2.5}},   {"gn", {7.5, 2.5}},   {"me", {7, 2.5}},  {"mso", {7, 2}},
    {"mio", {6.5, 3}}, {"ac", {10, 3}},     {"go", {12.5, 6}},    {"zy", {7.5, 3}},  {"sC", {10.5, 2.5}},
    {"iC", {11, 2.5}}, {"ecm2", {26, 7}},   {"ecm2i", {22, 6.5}}, {"mr", {19.5, 5}}, {"mmb", {11, 4}}};

// Section 2: Rhine 1983, by Rhine's site name.
const std::map<std::string, double> k_rhine = {
    {"supraglabella", 4.5},      {"glabella", 4.5},         {"nasion", 7},
    {"end of nasals", 2.5},      {"mid-philtrum", 10},      {"upper lip margin", 11},
    {"lower lip margin", 12.25}, {"chin-lip fold", 10},     {"mental eminence", 13},
    {"beneath chin", 8},         {"frontal eminence L", 4}, {"supraorbital R", 8.5},
    {"suborbital L", 6.25},      {"inferior malar R", 12},  {"lateral orbit L", 11.5},
    {"zygomatic arch R", 7},     {"supraglenoid L", 6.25},  {"gonion R", 10.5},
    {"supra M2 L", 18},          {"occlusal line R", 17.5}, {"sub M2 L", 17}};

const std::string k_header = "landmark,mean_mm,sd_mm,sex,population,build,source\n";

std::string error_of(const std::string& csv) {
  try {
    parse_tissue_depth_table(csv, "user.csv", "user");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TissueDepthTable, BuiltInTablesAreListedAndTTableIsDefault) {
  const auto names = built_in_tissue_depth_table_names();
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "rhine_1983_sw_native_american_female_normal");
  EXPECT_EQ(names[1], "ttable_2023");
  EXPECT_EQ(default_tissue_depth_table_name(), "ttable_2023");
}

TEST(TissueDepthTable, TTableMatchesTheReferenceWithItsSource) {
  const TissueDepthTable table = built_in_tissue_depth_table("ttable_2023");
  EXPECT_EQ(table.origin, "built-in");
  ASSERT_EQ(table.rows.size(), k_ttable.size());
  bool cites = false;
  for (const std::string& c : table.comments)
    cites = cites || c.find("10.1007/s00414-023-03087-x") != std::string::npos;
  EXPECT_TRUE(cites) << "the table's header must name its source";
  const TissueDepths depths = select_tissue_depths(table);
  EXPECT_EQ(depths.group.sex, "pooled");
  EXPECT_EQ(depths.variant, "mean");
  for (const auto& [site, value] : k_ttable) {
    const TissueDepthEntry* e = depths.find_site(site);
    ASSERT_NE(e, nullptr) << site;
    EXPECT_EQ(e->mean_mm, value.first) << site;
    ASSERT_TRUE(e->sd_mm) << site;
    EXPECT_EQ(*e->sd_mm, value.second) << site;
    EXPECT_NE(e->source.find("Hona and Stephan 2024"), std::string::npos);
  }
  EXPECT_EQ(*depths.depth_mm("se'"), 6.0);
  EXPECT_EQ(*depths.depth_mm("zy_L"), 7.5);
  EXPECT_EQ(*depths.depth_mm("iM2'_R"), 22.0);
  EXPECT_FALSE(depths.depth_mm("po_L"));
}

TEST(TissueDepthTable, RhineTableMatchesTheReferenceAndHasNoSds) {
  const TissueDepths depths =
      select_tissue_depths(built_in_tissue_depth_table("rhine_1983_sw_native_american_female_normal"));
  EXPECT_EQ(depths.entries.size(), 21u);
  EXPECT_EQ(depths.group.sex, "female");
  EXPECT_EQ(depths.group.build, "normal");
  EXPECT_EQ(depths.group.population, "Southwestern Native American");
  for (const auto& [name, mm] : k_rhine) {
    const auto d = depths.depth_mm(name);
    ASSERT_TRUE(d) << name;
    EXPECT_EQ(*d, mm) << name;
  }
  for (const TissueDepthEntry& e : depths.entries) EXPECT_FALSE(e.sd_mm) << e.site;
  // Sites the Rhine table lacks are reported.
  const auto missing = depths.missing({"n", "op", "mmb_L", "zy_R"});
  ASSERT_EQ(missing.size(), 2u);
  EXPECT_EQ(missing[0], "op");
  EXPECT_EQ(missing[1], "mmb_L");
}

TEST(TissueDepthTable, SelectionUsesPooledValuesWithANoteAndRejectsMismatches) {
  const TissueDepthTable ttable = built_in_tissue_depth_table("ttable_2023");
  const TissueDepths female = select_tissue_depths(ttable, {"female", "", ""});
  ASSERT_EQ(female.notes.size(), 1u);
  EXPECT_NE(female.notes[0].find("pooled"), std::string::npos);
  const TissueDepthTable rhine = built_in_tissue_depth_table("rhine_1983_sw_native_american_female_normal");
  try {
    select_tissue_depths(rhine, {"male", "", ""});
    FAIL() << "a male group does not exist";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("female, Southwestern Native American, normal"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(select_tissue_depths(rhine, {"", "", "obese"}), InputError);
}

TEST(TissueDepthTable, BuildVariantsFromSdsAreMeanMinusAndPlusKSd) {
  const TissueDepthTable ttable = built_in_tissue_depth_table("ttable_2023");
  for (double k : {1.0, 2.0}) {
    const BuildVariants v = build_variants(ttable, {}, k);
    EXPECT_NE(v.method.find("SD"), std::string::npos);
    for (const auto& [site, value] : k_ttable) {
      EXPECT_DOUBLE_EQ(v.normal.find_site(site)->mean_mm, value.first) << site;
      EXPECT_DOUBLE_EQ(v.slender.find_site(site)->mean_mm, value.first - k * value.second) << site;
      EXPECT_DOUBLE_EQ(v.obese.find_site(site)->mean_mm, value.first + k * value.second) << site;
    }
  }
  // 3 SD below gnathion's mean (7.5 - 3 x 2.5) is zero: not a depth.
  EXPECT_THROW(build_variants(ttable, {}, 3.0), InputError);
}

TEST(TissueDepthTable, BuildVariantsComeFromTheTablesOwnGroups) {
  std::string csv = k_header;
  csv += "n,5,,male,test,slender,paper A\n";
  csv += "n,6,,male,test,normal,paper A\n";
  csv += "n,8,,male,test,obese,paper A\n";
  csv += "g,4,,male,test,slender,paper A\n";
  const TissueDepthTable table = parse_tissue_depth_table(csv, "builds.csv", "builds");
  const BuildVariants v = build_variants(table, {"male", "", ""});
  EXPECT_EQ(v.method, "table groups");
  EXPECT_EQ(*v.slender.depth_mm("n"), 5.0);
  EXPECT_EQ(*v.normal.depth_mm("n"), 6.0);
  EXPECT_EQ(*v.obese.depth_mm("n"), 8.0);
  EXPECT_EQ(*v.slender.depth_mm("g"), 4.0);
  EXPECT_FALSE(v.obese.depth_mm("g"));
  // By name, as jobs give the build.
  EXPECT_EQ(*v.of("slender").depth_mm("n"), 5.0);
  EXPECT_EQ(*v.of("normal").depth_mm("n"), 6.0);
  EXPECT_EQ(*v.of("obese").depth_mm("n"), 8.0);
  EXPECT_THROW(v.of("athletic"), InputError);
}

TEST(TissueDepthTable, TablesWithoutSdsOrBuildGroupsGiveNoVariants) {
  const TissueDepthTable rhine = built_in_tissue_depth_table("rhine_1983_sw_native_american_female_normal");
  try {
    build_variants(rhine);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("invented"), std::string::npos) << e.what();
  }
}

TEST(TissueDepthTable, HostileTablesNameFileLineAndField) {
  const auto expect = [](const std::string& row, const std::string& location, const std::string& words) {
    const std::string e = error_of(k_header + "n,6,1,pooled,p,pooled,src\n" + row);
    EXPECT_NE(e.find("user.csv:" + location), std::string::npos) << row << " -> " << e;
    EXPECT_NE(e.find(words), std::string::npos) << row << " -> " << e;
  };
  expect("g,nan,1,pooled,p,pooled,src\n", "line 3, field mean_mm", "finite");
  expect("g,inf,1,pooled,p,pooled,src\n", "line 3, field mean_mm", "finite");
  expect("g,-2,1,pooled,p,pooled,src\n", "line 3, field mean_mm", "not positive");
  expect("g,0,1,pooled,p,pooled,src\n", "line 3, field mean_mm", "not positive");
  expect("g,5,-1,pooled,p,pooled,src\n", "line 3, field sd_mm", "negative");
  expect("g,5,NaN,pooled,p,pooled,src\n", "line 3, field sd_mm", "finite");
  expect("glabela,5,1,pooled,p,pooled,src\n", "line 3, field landmark", "did you mean 'glabella'");
  expect("n,5,1,pooled,p,pooled,src\n", "line 3, field landmark", "also on line 2");
  expect("nasion,5,1,pooled,p,pooled,src\n", "line 3, field landmark", "given twice");
  expect("zy_L,5,1,pooled,p,pooled,src\n", "line 3, field landmark", "both sides");
  expect("po,5,1,pooled,p,pooled,src\n", "line 3, field landmark", "no skin landmark");
  expect("g,5,1,unknown,p,pooled,src\n", "line 3, field sex", "'female'");
  expect("g,5,1,pooled,p,chubby,src\n", "line 3, field build", "'obese'");
  expect("g,5,1,pooled,,pooled,src\n", "line 3, field population", "empty");
  expect("g,5,1,pooled,p,pooled,\n", "line 3, field source", "empty");
  expect("g,5,1,pooled,p,pooled\n", "line 3", "fields");
  // The same site in another group is fine.
  EXPECT_EQ(error_of(k_header + "n,6,1,pooled,p,pooled,src\nn,7,1,female,p,pooled,src\n"), "");
  // Skin landmark column must agree with the pairing.
  const std::string pair = error_of(
      "landmark,skin_landmark,mean_mm,sex,population,build,source\n"
      "n,sn',6,pooled,p,pooled,src\n");
  EXPECT_NE(pair.find("line 2, field skin_landmark"), std::string::npos) << pair;
  EXPECT_NE(error_of("landmark,mean_mm,sex,population,build\nn,6,pooled,p,pooled\n").find("'source'"),
            std::string::npos);
  EXPECT_NE(error_of("landmark,mean,sex,population,build,source\n").find("did you mean"), std::string::npos);
  EXPECT_NE(error_of(k_header).find("no rows"), std::string::npos);
}

TEST(TissueDepthTable, SkinNamesAndRhineNamesMapToTheirBoneSites) {
  const TissueDepthTable t = parse_tissue_depth_table(
      k_header + "se',6,1,pooled,p,pooled,src\nsupra M2,18,,pooled,p,pooled,src\n", "user.csv", "user");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].site, "n");
  EXPECT_EQ(t.rows[1].site, "ecm2");
  EXPECT_EQ(t.rows[1].line, 3);
}

TEST(TissueDepthTable, UserFilesLoadByPathAndUnknownNamesSuggest) {
  const auto dir = forensim::test::scratch_dir("tissue_depth_user");
  const auto path = dir / "my_table.csv";
  {
    std::ofstream out(path);
    out << "# my source\n" << k_header << "n,6.5,1.2,male,test population,normal,\"Someone 2020, J X 1:2\"\n";
  }
  const TissueDepthTable t = tissue_depth_table(path.string());
  EXPECT_EQ(t.name, "my_table");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0].source, "Someone 2020, J X 1:2");
  EXPECT_EQ(t.comments[0], "my source");
  try {
    tissue_depth_table("ttable_2032");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'ttable_2023'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(tissue_depth_table((dir / "absent.csv").string()), IoError);
  std::filesystem::remove_all(dir);
}

TEST(TissueDepthTable, OffsetBySdNeedsSds) {
  const TissueDepths ttable = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  const TissueDepths plus = offset_by_sd(ttable, 0.5);
  EXPECT_DOUBLE_EQ(*plus.depth_mm("go_L"), 12.5 + 0.5 * 6);
  EXPECT_EQ(plus.variant, "mean + 0.5 SD");
  EXPECT_NE(plus.find_site("go")->source.find("mean + 0.5 SD"), std::string::npos);
  const TissueDepths rhine =
      select_tissue_depths(built_in_tissue_depth_table("rhine_1983_sw_native_american_female_normal"));
  EXPECT_THROW(offset_by_sd(rhine, 1.0), InputError);
}

TEST(TissueDepthTable, SampledDepthsFollowTheTablesMeansAndSds) {
  const TissueDepths ttable = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  const TissueDepths a = sample_tissue_depths(ttable, 42, 3);
  const TissueDepths b = sample_tissue_depths(ttable, 42, 3);
  const TissueDepths c = sample_tissue_depths(ttable, 42, 4);
  bool differs = false;
  for (std::size_t i = 0; i < a.entries.size(); ++i) {
    EXPECT_EQ(a.entries[i].mean_mm, b.entries[i].mean_mm);
    differs = differs || a.entries[i].mean_mm != c.entries[i].mean_mm;
  }
  EXPECT_TRUE(differs);
  constexpr int members = 4000;
  double sum = 0.0, sum2 = 0.0, rhi_min = 1e9;
  for (int m = 0; m < members; ++m) {
    const TissueDepths s = sample_tissue_depths(ttable, 7, static_cast<std::uint64_t>(m));
    const double g = s.find_site("g")->mean_mm;  // 5.5 +- 1: truncation at 0 is negligible
    sum += g;
    sum2 += g * g;
    rhi_min = std::min(rhi_min, s.find_site("rhi")->mean_mm);
  }
  const double mean = sum / members;
  const double sd = std::sqrt(sum2 / members - mean * mean);
  EXPECT_NEAR(mean, 5.5, 3.0 * 1.0 / std::sqrt(double(members)));
  EXPECT_NEAR(sd, 1.0, 0.05);
  EXPECT_GT(rhi_min, 0.0);
  const TissueDepths rhine =
      select_tissue_depths(built_in_tissue_depth_table("rhine_1983_sw_native_american_female_normal"));
  EXPECT_THROW(sample_tissue_depths(rhine, 1, 0), InputError);
}
