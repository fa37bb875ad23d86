// The stages before the warp (src/reconstruct/reconstruct_inputs.*): bad jobs fail before any geometry is
// built, naming the input; a template head given to the stages gives what they build themselves.

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "craniofacial/template_head.hpp"
#include "reconstruct/reconstruct_inputs.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

ReconstructJob coarse_job() {
  ReconstructJob job;
  job.template_detail = "coarse";
  job.expressions.clear();
  return job;
}

/// The message of the InputError or IoError `body` throws ("" when it throws nothing or something else).
template <typename F>
std::string error_of(F&& body) {
  try {
    body();
  } catch (const InputError& e) {
    return e.what();
  } catch (const IoError& e) {
    return e.what();
  } catch (...) {
    return "other exception";
  }
  return "";
}

}  // namespace

TEST(ReconstructInputs, BadJobsFailBeforeTheTemplateNamingTheInput) {
  const std::filesystem::path dir = test::scratch_dir("reconstruct_inputs_bad");
  // Each case: a change to the coarse job, and a text the error must hold.
  const auto fails_naming = [](const std::function<void(ReconstructJob&)>& change, const std::string& text) {
    ReconstructJob job = coarse_job();
    change(job);
    const std::string message = error_of([&] { prepare_reconstruction(job); });
    EXPECT_NE(message.find(text), std::string::npos) << "'" << message << "' should name " << text;
  };
  fails_naming([](ReconstructJob& j) { j.expressions = {"smile", "smile"}; }, "listed twice");
  fails_naming([](ReconstructJob& j) { j.expressions = {"grin"}; }, "grin");
  fails_naming([&](ReconstructJob& j) { j.table = (dir / "no_table.csv").string(); }, "no_table.csv");
  const std::string skull = (dir / "skull.obj").string();
  fails_naming(
      [&](ReconstructJob& j) {
        j.skull = skull;
        j.landmarks = "template";
      },
      "template");
  fails_naming(
      [&](ReconstructJob& j) {
        j.skull = skull;
        j.evaluate = true;
      },
      "skull.obj");
  fails_naming([&](ReconstructJob& j) { j.skull = skull; }, "skull.obj");
  fails_naming([&](ReconstructJob& j) { j.ct = (dir / "missing.nrrd").string(); }, "missing.nrrd");
  fails_naming([&](ReconstructJob& j) { j.landmarks = (dir / "none.mrk.json").string(); }, "none.mrk.json");
  // A prebuilt template head stands for the built-in one only.
  ReconstructJob job = coarse_job();
  job.template_file = (dir / "head.template").string();
  EXPECT_THROW(prepare_reconstruction(job, std::make_shared<const TemplateHead>()), std::invalid_argument);
}

TEST(ReconstructInputs, APrebuiltTemplateGivesWhatTheStagesBuild) {
  ReconstructJob job = coarse_job();
  job.landmarks = "template";
  const ReconstructInputs built = prepare_reconstruction(job);
  auto head = std::make_shared<const TemplateHead>(make_template_head(template_head_options("coarse")));
  const ReconstructInputs given = prepare_reconstruction(job, head);
  EXPECT_EQ(given.head.get(), head.get());
  EXPECT_EQ(given.fitted.get(), head.get());  // template landmarks: nothing to carry
  ASSERT_EQ(built.head->skin.positions.size(), given.head->skin.positions.size());
  EXPECT_EQ(built.head->skin.positions, given.head->skin.positions);
  EXPECT_EQ(built.skull.mesh.positions, given.skull.mesh.positions);
  ASSERT_EQ(built.landmarks.size(), given.landmarks.size());
  for (std::size_t i = 0; i < built.landmarks.size(); ++i) {
    EXPECT_EQ(built.landmarks[i].name, given.landmarks[i].name);
    EXPECT_EQ(built.landmarks[i].position_mm, given.landmarks[i].position_mm);
  }
  EXPECT_EQ(built.landmark_origin, "the template's skull landmarks (placed by their definitions)");
  EXPECT_TRUE(built.known_frame.has_value());
  EXPECT_EQ(built.depths.entries.size(), given.depths.entries.size());
  EXPECT_GT(built.depths.entries.size(), 20u);
}
