#include "tet_io/pvd_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "support/test_support.hpp"
#include "tet_io/sample_tet_mesh.hpp"
#include "tet_io/xml_lite.hpp"

using namespace forensim;

TEST(PvdWriter, FileIsACompleteSeriesAfterEveryStep) {
  const auto dir = test::scratch_dir("pvd");
  const auto path = dir / "run.pvd";
  PvdSeries series(path);
  EXPECT_TRUE(read_pvd(path).empty());  // valid before the first step
  const double times[] = {0.0, 0.5, 1.0 / 3.0};
  const char* files[] = {"steps/step_0.vtu", "steps/a&b <1>.vtu", "steps/step_\"2\".vtu"};
  for (int i = 0; i < 3; ++i) {
    series.add(times[i], files[i]);
    const std::vector<PvdEntry> entries = read_pvd(path);
    ASSERT_EQ(entries.size(), static_cast<std::size_t>(i + 1));
    for (int k = 0; k <= i; ++k) {
      EXPECT_EQ(entries[k].time, times[k]);
      EXPECT_EQ(entries[k].file, files[k]);
    }
  }
  // ParaView's collection layout.
  const std::string text = test::slurp(path);
  const XmlDocument doc = parse_xml(text, path.string());
  EXPECT_EQ(doc.root.name, "VTKFile");
  EXPECT_EQ(*doc.root.attribute("type"), "Collection");
  ASSERT_NE(doc.root.child("Collection"), nullptr);
  EXPECT_EQ(doc.root.child("Collection")->children.size(), 3u);
  EXPECT_EQ(*doc.root.child("Collection")->children[0].attribute("part"), "0");
  // No temporary files left beside it.
  std::size_t files_in_dir = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files_in_dir;
  EXPECT_EQ(files_in_dir, 1u);
}

TEST(PvdWriter, ResumesFromEntries) {
  const auto path = test::scratch_dir("pvd") / "run.pvd";
  {
    PvdSeries series(path);
    series.add(1.0, "a.vtu");
  }
  PvdSeries resumed(path, read_pvd(path));
  resumed.add(2.0, "b.vtu");
  const auto entries = read_pvd(path);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].file, "b.vtu");
}

TEST(PvdWriter, RejectsNonFiniteTime) {
  PvdSeries series(test::scratch_dir("pvd") / "run.pvd");
  EXPECT_THROW(series.add(std::nan(""), "a.vtu"), InputError);
  EXPECT_THROW(series.add(1.0, ""), InputError);
  EXPECT_TRUE(series.entries().empty());
}
