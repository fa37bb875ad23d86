#include <gtest/gtest.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/metaimage_reader.hpp"
#include "volume/volume_reader.hpp"
#include "volume/voxel_data.hpp"

using namespace forensim;

namespace {

ScalarGrid test_grid() {
  ScalarGrid g = ScalarGrid::filled(6, 4, 5);
  g.spacing = Vec3(0.488, 0.488, 1.25);
  g.origin = Vec3(-120.5, -99.0, -300.75);
  g.direction = Eigen::AngleAxisd(-0.2, Vec3(1, 0.5, 0.1).normalized()).toRotationMatrix();
  for (std::size_t i = 0; i < g.values.size(); ++i)
    g.values[i] = static_cast<float>(std::cos(0.11 * double(i)) * 2048.0);
  return g;
}

void expect_same(const ScalarGrid& a, const ScalarGrid& b) {
  ASSERT_EQ(a.voxel_count(), b.voxel_count());
  EXPECT_EQ(a.nx, b.nx);
  EXPECT_EQ(a.nz, b.nz);
  EXPECT_EQ(a.spacing, b.spacing);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_LT((a.direction - b.direction).norm(), 1e-15);
  EXPECT_EQ(a.values, b.values);
}

}  // namespace

TEST(MetaImage, RoundTripMhaMhdRawZraw) {
  const auto dir = test::scratch_dir("mhd");
  const ScalarGrid g = test_grid();
  write_metaimage(dir / "local.mha", g);
  expect_same(read_metaimage(dir / "local.mha"), g);
  write_metaimage(dir / "raw.mhd", g, false);
  expect_same(read_volume(dir / "raw.mhd"), g);
  write_metaimage(dir / "z.mhd", g, true);
  EXPECT_TRUE(std::filesystem::exists(dir / "z.zraw"));
  expect_same(read_metaimage(dir / "z.mhd"), g);
  write_metaimage(dir / "zlocal.mha", g, true);
  expect_same(read_metaimage(dir / "zlocal.mha"), g);
}

TEST(MetaImage, BigEndianShortGzipAndHeaderSize) {
  const auto dir = test::scratch_dir("mhd_forms");
  std::string be;
  for (int v : {-1000, 0, 40, 3000, -1, 7}) {
    be += char((v >> 8) & 0xff);
    be += char(v & 0xff);
  }
  const std::string header =
      "ObjectType = Image\nNDims = 3\nDimSize = 3 2 1\nElementType = MET_SHORT\n"
      "BinaryDataByteOrderMSB = True\nElementSpacing = 0.5 0.5 2\nOffset = 1 2 3\n";
  write_file_atomic(dir / "gz.raw.gz", deflate_bytes(be, true));
  write_file_atomic(dir / "gz.mhd", header + "ElementDataFile = gz.raw.gz\n");
  write_file_atomic(dir / "skip.raw", std::string(17, '#') + be);
  write_file_atomic(dir / "skip.mhd", header + "HeaderSize = -1\nElementDataFile = skip.raw\n");
  write_file_atomic(dir / "skip17.mhd", header + "HeaderSize = 17\nElementDataFile = skip.raw\n");
  for (const char* name : {"gz.mhd", "skip.mhd", "skip17.mhd"}) {
    const ScalarGrid g = read_metaimage(dir / name);
    EXPECT_EQ(g.values, (std::vector<float>{-1000, 0, 40, 3000, -1, 7})) << name;
    EXPECT_EQ(g.origin, Vec3(1, 2, 3));
    EXPECT_EQ(g.spacing, Vec3(0.5, 0.5, 2));
  }
  // A header size one byte too large leaves the data one byte short.
  write_file_atomic(dir / "skip18.mhd", header + "HeaderSize = 18\nElementDataFile = skip.raw\n");
  EXPECT_THROW(read_metaimage(dir / "skip18.mhd"), InputError);
}
