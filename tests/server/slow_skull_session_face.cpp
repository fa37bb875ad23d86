// The skull editor's session and `forensim reconstruct` give one face for one skull: both run the library's
// reconstruction stages (src/reconstruct), here on a partial CT (the phantom with its top cut away), where the
// automatic landmarks complete the skull and the CT's bone edge is measured at its half-maximum height.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "craniofacial/template_head.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "reconstruct/reconstruct_face.hpp"
#include "server/server_fixture.hpp"
#include "server/skull_session.hpp"
#include "server/skull_session_request.hpp"
#include "support/test_support.hpp"
#include "volume/nrrd_reader.hpp"

using namespace forensim;
using test::floats;

namespace {

/// The phantom CT below `keep` of its height (superior slices dropped).
ScalarGrid lower_part(const ScalarGrid& ct, double keep) {
  ScalarGrid part = ct;
  part.nz = static_cast<int>(std::lround(keep * ct.nz));
  part.values.resize(part.voxel_count());
  return part;
}

}  // namespace

TEST(SkullSessionFace, IsTheFaceForensimReconstructGivesForThePartialCt) {
  const std::filesystem::path dir = test::scratch_dir("skull_session_face");
  const std::filesystem::path ct_path = dir / "partial_head.nrrd";
  write_nrrd(ct_path, lower_part(make_ct_head_phantom(), 0.8));

  // forensim reconstruct's job for this skull (its defaults, the coarse template, no expressions).
  ReconstructJob job;
  job.skull = ct_path.string();
  job.template_detail = "coarse";
  job.expressions.clear();
  const ReconstructedFace face = reconstruct_face(job);
  ASSERT_TRUE(face.inputs.detection.has_value());
  EXPECT_TRUE(face.inputs.completion.has_value()) << "the cut should leave landmarks outside the scan";
  EXPECT_TRUE(face.inputs.carried);
  EXPECT_TRUE(face.inputs.skull.seed_iso_value.has_value()) << "the half-maximum bone edge";

  // The session on the same file, with the server's prebuilt coarse template.
  SkullSessionRequest request;
  request.skull = ct_path.string();
  request.skull_label = "partial_head.nrrd";
  request.landmarks = "auto";
  request.template_detail = "coarse";
  auto head = std::make_shared<const TemplateHead>(make_template_head(template_head_options("coarse")));
  SkullSession session("a", head, request);
  const nlohmann::json described = session.describe(true);

  EXPECT_EQ(described["skull"]["triangles"].get<std::size_t>(), face.inputs.skull.mesh.triangle_count());
  EXPECT_EQ(described["skull"]["notes"].get<std::vector<std::string>>(), face.inputs.skull.notes);
  EXPECT_TRUE(described["detection"]["skull_completed"].get<bool>());
  const std::vector<float> positions = floats(described["face"]["positions_f32"]);
  ASSERT_EQ(positions.size(), 3 * face.skin.positions.size());
  double largest = 0.0;
  for (std::size_t v = 0; v < face.skin.positions.size(); ++v)
    for (int c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(double(positions[3 * v + c]) - face.skin.positions[v][c]));
  EXPECT_LT(largest, 1e-3) << "mm; float32 holds the session's positions";
  ASSERT_EQ(described["landmarks"].size(), face.reconstruction->result().skull_landmarks.size());
}
