#include <gtest/gtest.h>

#include <fstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/nrrd_reader.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

ScalarGrid test_grid() {
  ScalarGrid g = ScalarGrid::filled(7, 5, 3);
  g.spacing = Vec3(0.7, 0.9, 2.5);
  g.origin = Vec3(-101.3, 12.25, 1e-3);
  g.direction = Eigen::AngleAxisd(0.4, Vec3(0.2, 1, -0.3).normalized()).toRotationMatrix();
  for (std::size_t i = 0; i < g.values.size(); ++i) g.values[i] = static_cast<float>(std::sin(0.37 * double(i)) * 1e3);
  g.values[3] = -0.0f;
  g.values[5] = 1e-30f;
  return g;
}

void expect_same(const ScalarGrid& a, const ScalarGrid& b, double tol = 0.0) {
  ASSERT_EQ(a.nx, b.nx);
  ASSERT_EQ(a.ny, b.ny);
  ASSERT_EQ(a.nz, b.nz);
  EXPECT_LE((a.spacing - b.spacing).norm(), tol);
  EXPECT_LE((a.origin - b.origin).norm(), tol);
  EXPECT_LE((a.direction - b.direction).norm(), tol + 1e-15);
  ASSERT_EQ(a.values.size(), b.values.size());
  for (std::size_t i = 0; i < a.values.size(); ++i) ASSERT_EQ(a.values[i], b.values[i]) << "voxel " << i;
}

void write_text(const std::filesystem::path& p, const std::string& s) {
  write_file_atomic(p, s);
}

std::string le16(const std::vector<int>& v) {
  std::string s;
  for (int x : v) {
    s += char(x & 0xff);
    s += char((x >> 8) & 0xff);
  }
  return s;
}

}  // namespace

TEST(Nrrd, RoundTripAttachedAndDetachedRawAndGzip) {
  const auto dir = test::scratch_dir("nrrd");
  const ScalarGrid g = test_grid();
  for (const char* name : {"a.nrrd", "b.nhdr"}) {
    for (const bool gzip : {false, true}) {
      const auto path = dir / (std::string(gzip ? "gz_" : "raw_") + name);
      write_nrrd(path, g, gzip);
      expect_same(read_nrrd(path), g, 1e-12);
      expect_same(read_volume(path), g, 1e-12);
    }
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "gz_b.raw.gz"));
  EXPECT_TRUE(std::filesystem::exists(dir / "raw_b.raw"));
}

TEST(Nrrd, MultiFilePatternAndList) {
  const auto dir = test::scratch_dir("nrrd_multi");
  // 3 x 2 x 4 int16 big-endian volume, one file per slice numbered 10, 8, 6, 4 (descending step) with a 3-byte
  // per-file skip.
  std::string header = "NRRD0005\n# comment\ntype: short\ndimension: 3\nsizes: 3 2 4\nendian: big\nencoding: raw\n";
  header += "byte skip: 3\nspacings: 1.5 2 3\nkey:=value\n";
  for (int k = 0; k < 4; ++k) {
    std::string data = "xyz";
    for (int i = 0; i < 6; ++i) {
      const int v = 100 * k - 7 * i - 20;
      data += char((v >> 8) & 0xff);
      data += char(v & 0xff);
    }
    write_text(dir / ("slice" + std::to_string(10 - 2 * k) + ".raw"), data);
  }
  write_text(dir / "pattern.nhdr", header + "data file: slice%d.raw 10 4 -2\n");
  write_text(dir / "list.nhdr", header + "data file: LIST 2\nslice10.raw\nslice8.raw\nslice6.raw\nslice4.raw\n");
  for (const char* name : {"pattern.nhdr", "list.nhdr"}) {
    const ScalarGrid g = read_nrrd(dir / name);
    ASSERT_EQ(g.voxel_count(), 24u);
    for (int k = 0; k < 4; ++k) {
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 3; ++i) EXPECT_EQ(g.at(i, j, k), 100 * k - 7 * (j * 3 + i) - 20);
      }
    }
    EXPECT_EQ(g.spacing, Vec3(1.5, 2, 3));
  }
  // Zero-padded pattern with a two-slice sub-dimension: 2 files of 2 slices each.
  for (int f = 0; f < 2; ++f) {
    std::string data;
    for (int i = 0; i < 4; ++i) data += char(f * 4 + i);
    write_text(dir / ("part00" + std::to_string(f) + ".bin"), data);
  }
  write_text(dir / "sub.nhdr",
             "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 1 4\nencoding: raw\ndata file: part%03d.bin 0 1 1 3\n");
  EXPECT_THROW(read_nrrd(dir / "sub.nhdr"), InputError);  // subdim 3 = whole volume per file, but 2 files
  write_text(dir / "sub.nhdr",
             "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: part%03d.bin 0 1 1 2\n");
  const ScalarGrid sub = read_nrrd(dir / "sub.nhdr");
  for (int i = 0; i < 8; ++i) EXPECT_EQ(sub.values[std::size_t(i)], float(i));
}

TEST(Nrrd, SpaceDirectionsRasTextAndSkips) {
  const auto dir = test::scratch_dir("nrrd_space");
  write_text(dir / "ras.nrrd",
             "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 1 2\nencoding: ascii\nspace: right-anterior-superior\n"
             "space directions: (0,-2,0) (3,0,0) (0,0,1.5)\nspace origin: (10,20,30)\n\n1.5 -2\n3e2, 4\n");
  const ScalarGrid g = read_nrrd(dir / "ras.nrrd");
  EXPECT_EQ(g.values, (std::vector<float>{1.5f, -2.0f, 300.0f, 4.0f}));
  EXPECT_EQ(g.spacing, Vec3(2, 3, 1.5));
  EXPECT_EQ(g.origin, Vec3(-10, -20, 30));  // RAS -> LPS
  EXPECT_EQ(g.direction.col(0), Vec3(0, 1, 0));
  EXPECT_EQ(g.direction.col(1), Vec3(-3, 0, 0).normalized());
  // line skip + byte skip -1 on a detached raw file with a text preamble, little-endian uint16.
  write_text(dir / "data.bin", "line one\nline two\nGARBAGE" + le16({1, 2, 65535, 4}));
  write_text(dir / "skip.nhdr",
             "NRRD0004\ntype: uint16\ndimension: 2\nsizes: 2 2\nendian: little\nencoding: raw\nline skip: 2\n"
             "byte skip: -1\ndata file: data.bin\n");
  const ScalarGrid s = read_nrrd(dir / "skip.nhdr");
  EXPECT_EQ(s.nz, 1);
  EXPECT_EQ(s.values, (std::vector<float>{1, 2, 65535, 4}));
}

TEST(Nrrd, ShortDataNamesExpectedAndActualBytes) {
  const auto dir = test::scratch_dir("nrrd_short");
  write_text(
      dir / "short.nrrd",
      "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 4 2\nendian: little\nencoding: raw\n\n" + std::string(40, 'x'));
  try {
    read_nrrd(dir / "short.nrrd");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("64 bytes"), std::string::npos) << what;
    EXPECT_NE(what.find("short.nrrd"), std::string::npos) << what;
  }
}

TEST(Nrrd, HeadCtDetachedMultiFile) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  const ScalarGrid ct = read_volume(path);
  EXPECT_EQ(ct.nx, 64);
  EXPECT_EQ(ct.ny, 64);
  EXPECT_EQ(ct.nz, 93);
  EXPECT_EQ(ct.spacing, Vec3(3.2, 3.2, 1.5));
  const auto [lo, hi] = ct.value_range();
  EXPECT_EQ(lo, 0.0f);
  EXPECT_EQ(hi, 3926.0f);  // SOURCE.md: values 0..3926
  // Slice N is file quarter.N: voxel (5, 7) of slice 40 is bytes 2*(7*64+5) of quarter.40.
  std::ifstream in(path.parent_path() / "quarter.40", std::ios::binary);
  in.seekg(2 * (7 * 64 + 5));
  unsigned char b[2];
  in.read(reinterpret_cast<char*>(b), 2);
  EXPECT_EQ(ct.at(5, 7, 39), float(b[0] | (b[1] << 8)));
}
