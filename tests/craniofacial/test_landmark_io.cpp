#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "craniofacial/landmark_io.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

LandmarkSet sample_set() {
  LandmarkSet set("skull");
  set.add({"n", Vec3(0.125, -91.3, 12.75), LandmarkSource::imported, 1.0});
  set.add({"zy_L", Vec3(66.1, -18.2, -3.3), LandmarkSource::detected, 0.8125});
  set.add({"zy_R", Vec3(-65.9, -18.4, -3.1), LandmarkSource::detected, 0.75});
  set.add({"se'", Vec3(0.1, -97.3, 12.7), LandmarkSource::edited, 1.0});
  set.add({"po_L", Vec3(70.0 / 3.0, 1e-7, 1e5), LandmarkSource::imported, 1.0});
  return set;
}

void expect_same(const LandmarkSet& a, const LandmarkSet& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    EXPECT_EQ(a[i].position_mm, b[i].position_mm) << a[i].name;  // bit-exact: shortest round-trip decimals
    EXPECT_EQ(a[i].source, b[i].source) << a[i].name;
    EXPECT_EQ(a[i].confidence, b[i].confidence) << a[i].name;
  }
}

std::string error_of(const std::string& json, const LandmarkReadOptions& options = {}) {
  try {
    parse_markups_json(json, "in.mrk.json", options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(LandmarkIo, MarkupsRoundTripInLpsAndRas) {
  const LandmarkSet set = sample_set();
  for (CoordinateSystem cs : {CoordinateSystem::lps, CoordinateSystem::ras}) {
    const std::string text = markups_json_text(set, {cs});
    const nlohmann::json doc = nlohmann::json::parse(text);
    EXPECT_EQ(doc["markups"][0]["coordinateSystem"], to_string(cs));
    EXPECT_EQ(doc["markups"][0]["type"], "Fiducial");
    EXPECT_EQ(doc["markups"][0]["controlPoints"][1]["label"], "zy_L");
    EXPECT_EQ(doc["markups"][0]["controlPoints"][1]["positionStatus"], "defined");
    const double file_x = doc["markups"][0]["controlPoints"][1]["position"][0];
    EXPECT_EQ(file_x, cs == CoordinateSystem::ras ? -66.1 : 66.1);
    expect_same(parse_markups_json(text, "mem"), set);
  }
}

TEST(LandmarkIo, SlicerRasFileOpensAtTheRightLpsCoordinates) {
  // As Slicer writes it, with the minimum keys and RAS coordinates.
  const std::string ras =
      R"({"@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#",
    "markups": [{"type": "Fiducial", "coordinateSystem": "RAS", "coordinateUnits": "mm", "controlPoints": [
      {"id": "1", "label": "Nasion", "description": "", "position": [1.5, 90.25, 12.0], "positionStatus": "defined"},
      {"id": "2", "label": "zy-l", "position": [-66.0, 18.0, -3.0], "positionStatus": "defined"},
      {"id": "3", "label": "g", "position": [0.0, 0.0, 0.0], "positionStatus": "undefined"}]}]})";
  const LandmarkSet set = parse_markups_json(ras, "ras.mrk.json");
  ASSERT_EQ(set.size(), 2u);  // the undefined point is skipped
  EXPECT_EQ(set[0].name, "n");
  EXPECT_EQ(set[0].position_mm, Vec3(-1.5, -90.25, 12.0));
  EXPECT_EQ(set[1].name, "zy_L");
  EXPECT_EQ(set[1].position_mm, Vec3(66.0, -18.0, -3.0));
  EXPECT_EQ(set[1].source, LandmarkSource::imported);
  EXPECT_EQ(set[1].confidence, 1.0);
  // The same points written in LPS read to the same place.
  const std::string lps = markups_json_text(set, {CoordinateSystem::lps});
  expect_same(parse_markups_json(lps, "lps"), set);
  EXPECT_EQ(to_lps(from_lps(Vec3(1, 2, 3), CoordinateSystem::ras), CoordinateSystem::ras), Vec3(1, 2, 3));
}

TEST(LandmarkIo, MissingCoordinateSystemMeansLpsAndOtherMarkupsAreSkipped) {
  const std::string text = R"({"markups": [
      {"type": "Line", "controlPoints": [{"label": "x", "position": [1, 2, 3]}]},
      {"type": "Fiducial", "controlPoints": [{"label": "F-1", "position": [1, 2, 3]}]}]})";
  const LandmarkSet set = parse_markups_json(text, "m", {LandmarkNaming::keep, std::nullopt});
  ASSERT_EQ(set.size(), 1u);
  EXPECT_EQ(set[0].name, "F-1");
  EXPECT_EQ(set[0].position_mm, Vec3(1, 2, 3));
}

TEST(LandmarkIo, MalformedMarkupsGiveClearErrors) {
  const auto point = [](const std::string& cp, const std::string& extra = "") {
    return R"({"markups": [{"type": "Fiducial")" + extra + R"(, "controlPoints": [)" + cp + "]}]}";
  };
  EXPECT_NE(error_of("{\"markups\": [\n{\"type\": }]}").find("line 2"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("JSON object"), std::string::npos);
  EXPECT_NE(error_of("{\"points\": []}").find("\"markups\""), std::string::npos);
  EXPECT_NE(error_of("{\"markups\": [{\"type\": \"Line\"}]}").find("Fiducial"), std::string::npos);
  const std::string two = error_of(point(R"({"label": "n", "position": [1, 2]})"));
  EXPECT_NE(two.find("markups[0].controlPoints[0].position"), std::string::npos) << two;
  EXPECT_NE(error_of(point(R"({"label": "n", "position": [1, "2", 3]})")).find("not a number"), std::string::npos);
  EXPECT_NE(error_of(point(R"({"label": "n", "position": [1, 2, 1e999]})")).find("in.mrk.json"), std::string::npos);
  EXPECT_NE(error_of(point(R"({"position": [1, 2, 3]})")).find("label"), std::string::npos);
  EXPECT_NE(error_of(point(R"({"label": " ", "position": [1, 2, 3]})")).find("empty"), std::string::npos);
  const std::string unknown = error_of(point(R"({"label": "glabela", "position": [1, 2, 3]})"));
  EXPECT_NE(unknown.find("did you mean 'glabella'"), std::string::npos) << unknown;
  const std::string dup =
      error_of(point(R"({"label": "n", "position": [1, 2, 3]}, {"label": "Nasion", "position": [1, 2, 3]})"));
  EXPECT_NE(dup.find("given twice"), std::string::npos) << dup;
  EXPECT_NE(dup.find("controlPoints[0]"), std::string::npos) << dup;
  EXPECT_NE(error_of(point(R"({"label": "n", "position": [1, 2, 3]})", R"(, "coordinateSystem": "XYZ")"))
                .find("not LPS or RAS"),
            std::string::npos);
  EXPECT_NE(
      error_of(point(R"({"label": "n", "position": [1, 2, 3]})", R"(, "coordinateUnits": "um")")).find("only \"mm\""),
      std::string::npos);
  EXPECT_NE(
      error_of(point(R"({"label": "n", "position": [1, 2, 3], "description": "confidence=2"})")).find("confidence"),
      std::string::npos);
}

TEST(LandmarkIo, CsvRoundTripAndRasComment) {
  const LandmarkSet set = sample_set();
  for (CoordinateSystem cs : {CoordinateSystem::lps, CoordinateSystem::ras}) {
    expect_same(parse_landmark_csv(landmark_csv_text(set, {cs}), "mem"), set);
  }
  const LandmarkSet plain = parse_landmark_csv("name,x,y,z\nnasion,1,2,3\nLeft Porion,4,5,6\n", "p.csv");
  EXPECT_EQ(plain[0].name, "n");
  EXPECT_EQ(plain[1].name, "po_L");
  EXPECT_EQ(plain[1].position_mm, Vec3(4, 5, 6));
  const LandmarkSet ras = parse_landmark_csv("# coordinate system: RAS\nname,x,y,z\nn,1,2,3\n", "r.csv");
  EXPECT_EQ(ras[0].position_mm, Vec3(-1, -2, 3));
  const LandmarkSet forced = parse_landmark_csv("# coordinate system: RAS\nname,x,y,z\nn,1,2,3\n", "r.csv",
                                                {LandmarkNaming::canonical, CoordinateSystem::lps});
  EXPECT_EQ(forced[0].position_mm, Vec3(1, 2, 3));
}

TEST(LandmarkIo, MalformedCsvNamesLineAndField) {
  const auto message = [](const std::string& text) {
    try {
      parse_landmark_csv(text, "l.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("name,x,y,z\nn,1,nan,3\n").find("l.csv:line 2, field y"), std::string::npos);
  EXPECT_NE(message("name,x,y\nn,1,2\n").find("'z'"), std::string::npos);
  EXPECT_NE(message("name,x,y,z\nn,1,2,3\nn,1,2,3\n").find("first at line 2"), std::string::npos);
  EXPECT_NE(message("name,x,y,z\nnasoin,1,2,3\n").find("did you mean 'nasion'"), std::string::npos);
  EXPECT_NE(message("name,x,y,z,confidence\nn,1,2,3,7\n").find("field confidence"), std::string::npos);
  EXPECT_NE(message("name,x,y,z,source\nn,1,2,3,guessed\n").find("field source"), std::string::npos);
}

TEST(LandmarkIo, FilesAreWrittenAtomicallyAndChosenByExtension) {
  const auto dir = forensim::test::scratch_dir("landmark_io_files");
  const LandmarkSet set = sample_set();
  for (const std::string name : {"skull.mrk.json", "skull.csv"}) {
    write_landmarks(dir / name, set, {CoordinateSystem::ras});
    LandmarkSet back = read_landmarks(dir / name);
    EXPECT_EQ(back.name(), name);
    expect_same(back, set);
  }
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 2u) << "no temporary files are left behind";
  EXPECT_THROW(write_landmarks(dir / "skull.txt", set), InputError);
  { std::ofstream(dir / "old.fcsv") << "# Markups fiducial file version = 4.11\n"; }
  try {
    read_landmarks(dir / "old.fcsv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(".mrk.json"), std::string::npos);
  }
  EXPECT_THROW(read_landmarks(dir / "absent.mrk.json"), IoError);
  std::filesystem::remove_all(dir);
}
