// End-to-end runs of `forensim reconstruct`: the built-in skull on defaults writes every output, its landmark
// files read back to the positions the provenance records, the skin landmarks lie at skull + depth along the
// recorded directions; the CT head phantom's skull with those landmarks given in RAS through a job file (with
// a build variant from the table's SDs); automatic landmarks on the built-in skull, the CT phantom and the real
// CT.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {

const char* kSmall = "reconstruct --template-detail coarse --texture-size 128 --samples 1 ";

Vec3 vec(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// The built-in run, shared by the tests below (one template build).
const std::filesystem::path& builtin_run() {
  static const std::filesystem::path out = [] {
    const auto dir = test::scratch_dir("reconstruct_slow_builtin") / "run";
    const auto r = run_cli(std::string(kSmall) + "--picture-size 96 -o " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return dir;
  }();
  return out;
}

}  // namespace

TEST(SlowReconstructCli, DefaultsWriteEveryOutput) {
  const auto& out = builtin_run();
  for (const char* f : {"head.glb", "head.obj", "head.mtl", "head_epidermis.png", "head_normal.png", "skull.obj",
                        "skull_landmarks.mrk.json", "skin_landmarks.mrk.json", "render_front.png", "render_side.png",
                        "render_three_quarter.png", "render_textured.png", "reconstruction.png", "expressions.png",
                        "violations.json", "provenance.json", "run.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  }
  const std::string glb = read_file(out / "head.glb");
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  // The default expressions are the head's morph targets, named for Blender's shape keys, and each moves the face.
  EXPECT_NE(glb.find("targetNames"), std::string::npos);
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  const auto& targets = provenance["expressions"]["morph_targets"];
  ASSERT_EQ(targets.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string name = targets[i]["name"].get<std::string>();
    EXPECT_EQ(name, std::vector<std::string>({"smile", "frown", "surprise"})[i]);
    EXPECT_NE(glb.find("\"" + name + "\""), std::string::npos) << name;
    EXPECT_GT(targets[i]["max_displacement_mm"].get<double>(), 1.0) << name;
    EXPECT_LT(targets[i]["max_displacement_mm"].get<double>(), 30.0) << name;
  }
  // No temporary files left behind.
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  const auto run = nlohmann::json::parse(read_file(out / "run.json"));
  EXPECT_EQ(run["facts"]["given_pairs"].get<int>(), 36);
  EXPECT_EQ(run["facts"]["expressions"].get<int>(), 3);
  EXPECT_GT(run["facts"]["interpolated_pairs"].get<int>(), 0);
  const auto violations = nlohmann::json::parse(read_file(out / "violations.json"));
  EXPECT_TRUE(violations.contains("given_pairs_only"));
  EXPECT_TRUE(violations.contains("with_interpolated_landmarks"));
  // The built-in skull with the table's depths: no skull through the skin after the interpolated pairs.
  EXPECT_EQ(run["facts"]["violations_after"].get<int>(), 0);
  std::cout << "built-in skull: " << run["facts"]["seconds_total"] << " s; violations "
            << run["facts"]["violations_before"] << " -> " << run["facts"]["violations_after"] << "\n";
}

TEST(SlowReconstructCli, LandmarkFilesReadBackToTheRecordedPositions) {
  const auto& out = builtin_run();
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  const LandmarkSet skull = read_landmarks(out / "skull_landmarks.mrk.json");
  const LandmarkSet skin = read_landmarks(out / "skin_landmarks.mrk.json");
  const auto& items = provenance["landmarks"]["items"];
  ASSERT_EQ(skull.size(), items.size());
  for (const auto& item : items) {
    const Landmark& s = skull.at(item["name"].get<std::string>());
    EXPECT_LT((s.position_mm - vec(item["skull_mm"])).norm(), 1e-6) << s.name;
    EXPECT_EQ(to_string(s.source), item["source"].get<std::string>());
    // The skin landmark is skull + depth * direction (the table's depth along the skull normal).
    const Landmark& q = skin.at(item["skin_landmark"].get<std::string>());
    const Vec3 expected = vec(item["skull_mm"]) + item["depth_mm"].get<double>() * vec(item["direction"]);
    EXPECT_LT((q.position_mm - expected).norm(), 1e-6) << q.name;
    EXPECT_NEAR(vec(item["direction"]).norm(), 1.0, 1e-9);
    // The depth is the table's for the site.
    const auto depths = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
    EXPECT_NEAR(item["depth_mm"].get<double>(), *depths.depth_mm(s.name), 1e-12) << s.name;
  }
  // The skin-only points of the template (nose, mouth) come along.
  EXPECT_TRUE(skin.contains("prn'"));
  EXPECT_GT(skin.size(), skull.size());
}

TEST(SlowReconstructCli, CtPhantomWithRasLandmarksAndSlenderBuildFromAJobFile) {
  const auto& builtin = builtin_run();
  const auto dir = test::scratch_dir("reconstruct_slow_ct");
  // The built-in skull's landmarks, written in RAS: the command must read them back into LPS.
  const LandmarkSet skull = read_landmarks(builtin / "skull_landmarks.mrk.json");
  LandmarkWriteOptions ras;
  ras.coordinate_system = CoordinateSystem::ras;
  write_landmarks(dir / "skull_ras.mrk.json", skull, ras);
  {
    std::ofstream job(dir / "job.json");
    job << R"({"version": 1, "ct": "phantom", "landmarks": "skull_ras.mrk.json", "build": "slender",
               "template_detail": "coarse", "texture_size": 0, "picture_size": 0})";
  }
  const auto out = dir / "run";
  const auto r = run_cli("reconstruct --job " + (dir / "job.json").string() + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  EXPECT_EQ(provenance["skull"]["kind"], "ct");
  EXPECT_EQ(provenance["table"]["build"], "slender");
  const auto slender = offset_by_sd(select_tissue_depths(built_in_tissue_depth_table("ttable_2023")), -1.0);
  for (const auto& item : provenance["landmarks"]["items"]) {
    const std::string name = item["name"].get<std::string>();
    // LPS positions: the CT's bone surface lies within a voxel or two of the template skull's.
    EXPECT_LT((vec(item["skull_mm"]) - skull.at(name).position_mm).norm(), 4.0) << name;
    EXPECT_NEAR(item["depth_mm"].get<double>(), *slender.depth_mm(name), 1e-12) << name;
  }
  const auto run = nlohmann::json::parse(read_file(out / "run.json"));
  std::cout << "CT phantom: " << run["facts"]["seconds_total"] << " s; violations " << run["facts"]["violations_before"]
            << " -> " << run["facts"]["violations_after"] << "\n";
}

TEST(SlowReconstructCli, AutomaticLandmarksOnTheBuiltInSkullLandOnItsKnownLandmarks) {
  const auto& builtin = builtin_run();
  const LandmarkSet known = read_landmarks(builtin / "skull_landmarks.mrk.json");
  const auto dir = test::scratch_dir("reconstruct_slow_auto");
  const auto out = dir / "run";
  const auto r = run_cli(std::string(kSmall) + "--picture-size 0 --landmarks auto -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const LandmarkSet detected = read_landmarks(out / "skull_landmarks.mrk.json");
  ASSERT_EQ(detected.size(), known.size());
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  const auto& items = provenance["landmarks"]["items"];
  ASSERT_EQ(items.size(), known.size());
  for (const auto& item : items) {
    const std::string name = item["name"].get<std::string>();
    EXPECT_LT((detected.at(name).position_mm - known.at(name).position_mm).norm(), 2.0) << name;
    EXPECT_EQ(detected.at(name).source, LandmarkSource::detected) << name;
    EXPECT_EQ(item["source"], "detected") << name;
    // The confidence is the detection's, recorded in the provenance and in the markups file.
    const double confidence = item["confidence"].get<double>();
    EXPECT_GE(confidence, 0.0);
    EXPECT_LE(confidence, 1.0);
    EXPECT_NEAR(detected.at(name).confidence, confidence, 1e-3) << name;
  }
  EXPECT_EQ(provenance["landmarks"]["detection"]["landmarks"].size(), known.size());
  EXPECT_NE(provenance["landmarks"]["origin"].get<std::string>().find("detected"), std::string::npos);
}

TEST(SlowReconstructCli, CtPhantomWithAutomaticLandmarks) {
  const auto& builtin = builtin_run();
  const LandmarkSet known = read_landmarks(builtin / "skull_landmarks.mrk.json");
  const auto dir = test::scratch_dir("reconstruct_slow_ct_auto");
  const auto out = dir / "run";
  const auto r = run_cli(std::string(kSmall) + "--picture-size 0 --ct phantom -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;  // "auto" is the default for a CT
  const LandmarkSet detected = read_landmarks(out / "skull_landmarks.mrk.json");
  ASSERT_EQ(detected.size(), known.size());
  double worst = 0.0;
  for (const Landmark& l : detected.landmarks()) {
    // The CT's bone surface lies within a voxel or two (2 mm) of the template skull's.
    worst = std::max(worst, (l.position_mm - known.at(l.name).position_mm).norm());
    EXPECT_LT((l.position_mm - known.at(l.name).position_mm).norm(), 4.0) << l.name;
    EXPECT_EQ(l.source, LandmarkSource::detected);
  }
  const auto run = nlohmann::json::parse(read_file(out / "run.json"));
  std::cout << "CT phantom, automatic landmarks: largest distance from the template's " << worst << " mm; "
            << run["facts"]["seconds_total"] << " s\n";
}

TEST(SlowReconstructCli, RealCtWithAutomaticLandmarksEvaluatedAgainstItsFace) {
  FORENSIM_REQUIRE_DATA(ct, "ct-head-headsq/quarter.nhdr");
  const auto dir = test::scratch_dir("reconstruct_slow_headsq");
  const auto out = dir / "run";
  const auto r = run_cli(std::string(kSmall) + "--picture-size 128 --expressions none --axes auto --ct " + ct.string() +
                         " --landmarks auto --evaluate --measure-guides -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // run.json records the flags that ran.
  const auto run = nlohmann::json::parse(read_file(out / "run.json"));
  EXPECT_TRUE(run["job"]["evaluate"].get<bool>());
  EXPECT_TRUE(run["job"]["measure_guides"].get<bool>());
  // No skull through the skin once the interpolated and correction pairs are in (paper Figure 6b), after the
  // measured guides' second warp too; the given pairs alone leave thousands.
  const auto violations = nlohmann::json::parse(read_file(out / "violations.json"));
  std::cout << "headsq violations: given pairs only "
            << violations["given_pairs_only"]["skull_outside_skin"].get<int>() +
                   violations["given_pairs_only"]["skin_inside_skull"].get<int>()
            << ", interpolated pairs "
            << violations["before_correction"]["skull_outside_skin"].get<int>() +
                   violations["before_correction"]["skin_inside_skull"].get<int>()
            << ", with " << violations["correction"]["pairs"] << " correction pairs "
            << violations["with_interpolated_landmarks"]["skull_outside_skin"].get<int>() +
                   violations["with_interpolated_landmarks"]["skin_inside_skull"].get<int>()
            << "\n";
  EXPECT_GT(violations["given_pairs_only"]["skull_outside_skin"].get<int>(), 0);
  for (const char* stage : {"with_interpolated_landmarks", "after_guides"}) {
    ASSERT_TRUE(violations.contains(stage)) << stage;
    EXPECT_EQ(violations[stage]["skull_outside_skin"].get<int>(), 0) << stage;
    EXPECT_EQ(violations[stage]["skin_inside_skull"].get<int>(), 0) << stage;
  }
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  EXPECT_EQ(provenance["skull"]["kind"], "ct");
  for (const auto& item : provenance["landmarks"]["items"]) EXPECT_EQ(item["source"], "detected");
  const auto& detection = provenance["landmarks"]["detection"];
  std::cout << "headsq CT, automatic landmarks: similarity scale " << detection["similarity_scale"] << ", rms "
            << detection["similarity_rms_mm"] << " mm, non-rigid rms " << detection["non_rigid_rms_mm"] << " mm\n";
  // No vault and the neck in the scan: the template skull keeps an adult's size (it shrank to 0.59 before the
  // registration paired only where the CT has data), and the vault's landmarks lie outside the scan.
  EXPECT_GT(detection["similarity_scale"].get<double>(), 0.9);
  EXPECT_LT(detection["similarity_scale"].get<double>(), 1.1);
  std::vector<std::string> unseen;
  for (const auto& l : detection["landmarks"]) {
    if (!l["in_view"].get<bool>()) unseen.push_back(l["name"]);
  }
  EXPECT_NE(std::find(unseen.begin(), unseen.end(), "v"), unseen.end());
  EXPECT_EQ(std::find(unseen.begin(), unseen.end(), "n"), unseen.end());
  // At 3.2 mm voxels the CT shows no nasal bones: mn and rhi are left out, with the reason.
  ASSERT_TRUE(detection.contains("left_out"));
  std::vector<std::string> left_out;
  for (const auto& l : detection["left_out"]) left_out.push_back(l["name"]);
  EXPECT_EQ(left_out, (std::vector<std::string>{"mn", "rhi"}));
  // The evaluation against the CT's own face.
  const auto e = nlohmann::json::parse(read_file(out / "evaluation.json"));
  std::cout << "headsq evaluation: mean " << e["mean_abs_mm"] << " mm, RMS " << e["rms_mm"] << " mm, signed mean "
            << e["signed_mean_mm"] << " mm, " << e["within_percent"] << " % within 2.5 mm over " << e["area_mm2"]
            << " mm^2\n";
  for (const char* key : {"mean_abs_mm", "rms_mm", "signed_mean_mm", "within_share", "area_mm2"}) {
    EXPECT_TRUE(std::isfinite(e[key].get<double>())) << key;
  }
  EXPECT_LE(e["mean_abs_mm"].get<double>(), e["rms_mm"].get<double>());
  EXPECT_LE(std::abs(e["signed_mean_mm"].get<double>()), e["mean_abs_mm"].get<double>());
  // Measured 62.7 % here (coarse template, measured guides; the full template without guides gives 58.8 %) with
  // the template carried onto the skull by the landmarks' registration before the warp; literature 54-77 %.
  EXPECT_GT(e["within_share"].get<double>(), 0.54);
  // A face of about 100 x 150 mm or more: the region is the face, not a patch of it.
  EXPECT_GT(e["area_mm2"].get<double>(), 15000.0);
  EXPECT_TRUE(std::filesystem::exists(out / "evaluation.png"));
  EXPECT_TRUE(std::filesystem::exists(out / "evaluation_face.vtu"));
  EXPECT_TRUE(provenance["template"]["carried_onto_skull"].get<bool>());

  // The paper's fit, the template warped as it is (--no-carry): its given landmark pairs must also bend a generic
  // skull's head onto this skull, which leaves about three times as much skull through the skin (measured with the
  // coarse template: 5,900 against 1,900 vertices) and a face farther from the real one (51.5 against 62.7 %).
  const auto paper = dir / "paper";
  const auto q = run_cli(std::string(kSmall) + "--picture-size 0 --expressions none --ct " + ct.string() +
                         " --landmarks auto --evaluate --measure-guides --no-carry -o " + paper.string());
  ASSERT_EQ(q.exit_code, 0) << q.output;
  const auto count = [](const nlohmann::json& v) {
    return v["given_pairs_only"]["skull_outside_skin"].get<int>() +
           v["given_pairs_only"]["skin_inside_skull"].get<int>();
  };
  const auto paper_violations = nlohmann::json::parse(read_file(paper / "violations.json"));
  const auto paper_e = nlohmann::json::parse(read_file(paper / "evaluation.json"));
  std::cout << "headsq without the carry: given pairs leave " << count(paper_violations)
            << " violations (carried: " << count(violations) << "), " << paper_e["within_percent"]
            << " % within 2.5 mm\n";
  EXPECT_FALSE(
      nlohmann::json::parse(read_file(paper / "provenance.json"))["template"]["carried_onto_skull"].get<bool>());
  EXPECT_GT(count(paper_violations), 2 * count(violations));
  EXPECT_GT(e["within_share"].get<double>(), paper_e["within_share"].get<double>());
}

TEST(SlowReconstructCli, UncertaintyEnsembleWritesTheSpreadPerVertex) {
  const auto dir = test::scratch_dir("reconstruct_slow_uncertainty");
  {
    std::ofstream job(dir / "job.json");
    job << R"({"version": 1, "uncertainty": {"samples": 4, "seed": 3}})";
  }
  nlohmann::json spread[2];
  for (int k = 0; k < 2; ++k) {
    const auto out = dir / ("run" + std::to_string(k));
    // The second run on one thread: the ensemble does not depend on the thread count.
    const std::string threads = k == 1 ? "--threads 1 " : "";
    const auto r = run_cli(threads + std::string(kSmall) + "--picture-size 96 --job " + (dir / "job.json").string() +
                           " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out / "render_uncertainty.png"));
    EXPECT_TRUE(std::filesystem::exists(out / "head_uncertainty.vtu"));
    spread[k] = nlohmann::json::parse(read_file(out / "uncertainty.json"));
    const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
    EXPECT_EQ(provenance["uncertainty"]["samples"], 4);
    EXPECT_EQ(provenance["uncertainty"]["seed"], 3);
  }
  // One value per head.obj vertex, none negative, the largest recorded.
  const std::string obj = read_file(dir / "run0" / "head.obj");
  std::size_t vertices = 0;
  for (std::size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) ++vertices;
  const auto& values = spread[0]["vertex_spread_mm"];
  ASSERT_EQ(values.size(), vertices);
  double largest = 0.0;
  for (const auto& v : values) {
    EXPECT_GE(v.get<double>(), 0.0);
    largest = std::max(largest, v.get<double>());
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_DOUBLE_EQ(spread[0]["max_spread_mm"].get<double>(), largest);
  EXPECT_EQ(spread[0]["vertex_spread_mm"], spread[1]["vertex_spread_mm"]);
  std::cout << "uncertainty (4 samples): max spread " << largest << " mm, mean "
            << spread[0]["mean_spread_mm"].get<double>() << " mm\n";
}

// --bone-edge half-maximum on the CT phantom: the threshold half-way between its soft tissue (1000) and bone (1800),
// in the provenance, and the detected landmarks still within a voxel or two of the template skull's (its thin
// alveolar bone kept by the plate model: an iso-surface at the threshold loses it and prosthion lands 7 mm off).
TEST(SlowReconstructCli, CtPhantomBoneAtItsHalfMaximumEdge) {
  const auto& builtin = builtin_run();
  const LandmarkSet known = read_landmarks(builtin / "skull_landmarks.mrk.json");
  const auto dir = test::scratch_dir("reconstruct_slow_ct_half_maximum");
  const auto out = dir / "run";
  const auto r =
      run_cli(std::string(kSmall) + "--picture-size 0 --ct phantom --bone-edge half-maximum -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  EXPECT_NEAR(provenance["skull"]["bone_iso"].get<double>(), 1400.0, 15.0);
  EXPECT_EQ(provenance["skull"]["bone_threshold"]["seed_iso"].get<double>(), 1150.0);
  EXPECT_GT(provenance["skull"]["bone_threshold"]["profiles"].get<int>(), 1000);
  const LandmarkSet detected = read_landmarks(out / "skull_landmarks.mrk.json");
  ASSERT_EQ(detected.size(), known.size());
  for (const Landmark& l : detected.landmarks()) {
    EXPECT_LT((l.position_mm - known.at(l.name).position_mm).norm(), 4.0) << l.name;
  }
  // Both ways of fixing the bone surface at once are refused, naming the option.
  const auto both = run_cli(std::string(kSmall) +
                            "--picture-size 0 --ct phantom --bone-edge half-maximum "
                            "--bone-iso 1300 -o " +
                            (dir / "both").string());
  EXPECT_NE(both.exit_code, 0);
  EXPECT_NE(both.output.find("--bone-edge"), std::string::npos) << both.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "both" / "provenance.json"));
}
