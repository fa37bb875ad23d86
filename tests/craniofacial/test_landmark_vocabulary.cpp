#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"

using namespace forensim;

namespace {

const LandmarkVocabulary& vocabulary() {
  return LandmarkVocabulary::built_in();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The 2023 T-Table's bone -> skin pairs as shared/reference/tissue-depth.md lists them (ecm2 -> iM2' is the
// mandibular point, named ecm2i in forensim).
const std::vector<std::pair<std::string, std::string>> k_ttable_pairs = {
    {"op", "op'"},    {"v", "v'"},       {"g", "g'"},   {"n", "se'"},   {"mn", "mn'"}, {"rhi", "rhi'"}, {"ss", "sn'"},
    {"mp", "mp'"},    {"pr", "ls'"},     {"id", "li'"}, {"sm", "sm'"},  {"pg", "pg'"}, {"gn", "gn'"},   {"me", "me'"},
    {"mso", "mso'"},  {"mio", "mio'"},   {"ac", "ac'"}, {"go", "go'"},  {"zy", "zy'"}, {"sC", "sC'"},   {"iC", "iC'"},
    {"ecm2", "sM2'"}, {"ecm2i", "iM2'"}, {"mr", "mr'"}, {"mmb", "mmb'"}};
const std::set<std::string> k_ttable_bilateral = {"mso", "mio",  "ac",    "go", "zy", "sC",
                                                  "iC",  "ecm2", "ecm2i", "mr", "mmb"};

}  // namespace

TEST(LandmarkVocabulary, EveryTTableSiteIsPairedBoneToSkin) {
  for (const auto& [bone, skin] : k_ttable_pairs) {
    const auto b = vocabulary().find_site(bone);
    const auto s = vocabulary().find_site(skin);
    ASSERT_TRUE(b) << bone;
    ASSERT_TRUE(s) << skin;
    const LandmarkSite& bs = vocabulary().sites()[*b];
    const LandmarkSite& ss = vocabulary().sites()[*s];
    EXPECT_EQ(bs.abbreviation, bone);
    EXPECT_EQ(bs.surface, LandmarkSurface::bone) << bone;
    EXPECT_EQ(ss.surface, LandmarkSurface::skin) << skin;
    EXPECT_EQ(bs.pair, skin);
    EXPECT_EQ(ss.pair, bone);
    const Laterality expected = k_ttable_bilateral.count(bone) ? Laterality::bilateral : Laterality::midline;
    EXPECT_EQ(bs.laterality, expected) << bone;
    EXPECT_EQ(ss.laterality, expected) << skin;
    EXPECT_FALSE(bs.definition.empty()) << bone;
    EXPECT_FALSE(bs.full_name.empty()) << bone;
  }
}

TEST(LandmarkVocabulary, PairingOfConcreteLandmarksKeepsTheSide) {
  const LandmarkRef zy_l = vocabulary().resolve("zy_L", "test", "");
  const auto skin = vocabulary().paired(zy_l);
  ASSERT_TRUE(skin);
  EXPECT_EQ(vocabulary().name(*skin), "zy'_L");
  EXPECT_EQ(vocabulary().name(*vocabulary().paired(*skin)), "zy_L");
  EXPECT_EQ(vocabulary().name(*vocabulary().paired(vocabulary().resolve("n", "test", ""))), "se'");
  EXPECT_FALSE(vocabulary().paired(vocabulary().resolve("po_L", "test", "")));
}

TEST(LandmarkVocabulary, RhineSitesAreTenMidlineAndElevenBilateralEachWithABoneSite) {
  const auto& rhine = vocabulary().rhine_sites();
  ASSERT_EQ(rhine.size(), 21u);
  int midline = 0;
  std::set<std::string> bone_sites;
  for (const RhineSite& r : rhine) {
    if (r.laterality == Laterality::midline) ++midline;
    const auto site = vocabulary().find_site(r.name);
    ASSERT_TRUE(site) << r.name;
    const LandmarkSite& s = vocabulary().sites()[*site];
    EXPECT_EQ(s.abbreviation, r.bone_site) << r.name;
    EXPECT_EQ(s.surface, LandmarkSurface::bone);
    EXPECT_FALSE(s.pair.empty()) << r.name << " needs a skin pair to take a depth";
    EXPECT_EQ(s.laterality, r.laterality) << r.name;
    if (r.same_as_ttable) {
      bool in_ttable = false;
      for (const auto& p : k_ttable_pairs) in_ttable = in_ttable || p.first == r.bone_site;
      EXPECT_TRUE(in_ttable) << r.name;
    }
    bone_sites.insert(r.bone_site);
  }
  EXPECT_EQ(midline, 10);
  EXPECT_EQ(bone_sites.size(), 21u) << "two Rhine sites share a bone site";
}

TEST(LandmarkVocabulary, LookupAcceptsAliasesSidesAndPrimes) {
  const auto canonical = [](const std::string& name) { return vocabulary().canonical_name(name, "test", ""); };
  EXPECT_EQ(canonical("Nasion"), "n");
  EXPECT_EQ(canonical("zy-l"), "zy_L");
  EXPECT_EQ(canonical("left zygion"), "zy_L");
  EXPECT_EQ(canonical("Zygion (right)"), "zy_R");
  EXPECT_EQ(canonical("zy'_R"), "zy'_R");
  EXPECT_EQ(canonical("zy_R'"), "zy'_R");
  EXPECT_EQ(canonical("sellion"), "se'");
  EXPECT_EQ(canonical("se\xE2\x80\x99"), "se'");  // typographic apostrophe
  EXPECT_EQ(canonical("supradentale"), "pr");
  EXPECT_EQ(canonical("end of nasals"), "rhi");
  EXPECT_EQ(canonical("supra M2 L"), "ecm2_L");
  EXPECT_EQ(canonical("sub M2 right"), "ecm2i_R");
  EXPECT_EQ(canonical("or_L"), "or_L");
  EXPECT_EQ(canonical("sc_l"), "sC_L");
}

TEST(LandmarkVocabulary, EveryCanonicalNameResolvesToItself) {
  std::set<std::string> seen;
  std::size_t expected = 0;
  for (const LandmarkSite& s : vocabulary().sites()) expected += s.laterality == Laterality::midline ? 1 : 2;
  std::size_t total = 0;
  for (LandmarkSurface surface : {LandmarkSurface::bone, LandmarkSurface::skin}) {
    for (const std::string& name : vocabulary().landmark_names(surface)) {
      EXPECT_EQ(vocabulary().canonical_name(name, "test", ""), name);
      EXPECT_EQ(vocabulary().site(vocabulary().resolve(name, "test", "")).surface, surface) << name;
      EXPECT_TRUE(seen.insert(name).second) << name << " twice";
      ++total;
    }
  }
  EXPECT_EQ(total, expected);
}

TEST(LandmarkVocabulary, UnknownNamesSuggestTheNearest) {
  const std::string e = error_of([] { vocabulary().resolve("nasoin", "skull.mrk.json", "point 3"); });
  EXPECT_NE(e.find("skull.mrk.json"), std::string::npos) << e;
  EXPECT_NE(e.find("point 3"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'nasion'"), std::string::npos) << e;
  const std::string g = error_of([] { vocabulary().resolve("glabela", "f", ""); });
  EXPECT_NE(g.find("did you mean 'glabella'"), std::string::npos) << g;
  const std::string z = error_of([] { vocabulary().resolve("zy_X", "f", ""); });
  EXPECT_NE(z.find("unknown landmark"), std::string::npos) << z;
}

TEST(LandmarkVocabulary, SidesMustFitTheSite) {
  const std::string midline = error_of([] { vocabulary().resolve("n_L", "f", ""); });
  EXPECT_NE(midline.find("midline"), std::string::npos) << midline;
  const std::string bilateral = error_of([] { vocabulary().resolve("zygion", "f", ""); });
  EXPECT_NE(bilateral.find("zy_L"), std::string::npos) << bilateral;
  const std::string sided_site = error_of([] { vocabulary().resolve_site("zy_L", "table.csv", "line 4"); });
  EXPECT_NE(sided_site.find("both sides"), std::string::npos) << sided_site;
  EXPECT_EQ(vocabulary().sites()[vocabulary().resolve_site("zygion", "t", "")].abbreviation, "zy");
}

TEST(LandmarkVocabulary, CollidingNamesAreRejected) {
  std::vector<LandmarkSite> sites = {
      {"a", "alpha", "", LandmarkSurface::bone, Laterality::midline, "", {}, "test"},
      {"b", "Alpha", "", LandmarkSurface::bone, Laterality::midline, "", {}, "test"},
  };
  EXPECT_THROW(LandmarkVocabulary(sites, {}), std::logic_error);
  sites[1].full_name = "beta";
  sites[0].pair = "b";  // b does not pair back
  EXPECT_THROW(LandmarkVocabulary(sites, {}), std::logic_error);
  sites[0].pair.clear();
  EXPECT_NO_THROW(LandmarkVocabulary(sites, {}));
}
