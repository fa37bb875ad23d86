#include <gtest/gtest.h>

// GDCM's headers live in /usr/include/gdcm-3.0, which only the volume library (not its tests) has on its include
// path; its headers include each other with quotes, so naming the folder here is enough.
#include <gdcm-3.0/gdcmAttribute.h>
#include <gdcm-3.0/gdcmImageWriter.h>
#include <gdcm-3.0/gdcmMediaStorage.h>
#include <gdcm-3.0/gdcmTrace.h>
#include <gdcm-3.0/gdcmUIDGenerator.h>

#include <cstring>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/dicom_reader.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

struct SliceSpec {
  int columns = 6, rows = 4;
  Vec3 position = Vec3::Zero();
  Vec3 row_direction = Vec3::UnitX(), column_direction = Vec3::UnitY();
  double pixel_spacing_x = 0.5, pixel_spacing_y = 0.75;
  double slope = 1.0, intercept = -1024.0;
  int k = 0;  // stored value pattern offset
  std::string series_uid;
};

std::int16_t stored_value(int i, int j, int k) {
  return static_cast<std::int16_t>(100 * k + 10 * j + i);
}

void write_slice(const std::filesystem::path& path, const SliceSpec& s) {
  gdcm::Trace::WarningOff();
  gdcm::ImageWriter writer;
  gdcm::Image& image = writer.GetImage();
  image.SetNumberOfDimensions(3);  // with 2, GDCM keeps only two origin components
  const unsigned dims[3] = {unsigned(s.columns), unsigned(s.rows), 1};
  image.SetDimensions(dims);
  image.SetPixelFormat(gdcm::PixelFormat(gdcm::PixelFormat::INT16));
  image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
  image.SetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
  const double origin[3] = {s.position.x(), s.position.y(), s.position.z()};
  image.SetOrigin(origin);
  const double cosines[6] = {s.row_direction.x(),    s.row_direction.y(),    s.row_direction.z(),
                             s.column_direction.x(), s.column_direction.y(), s.column_direction.z()};
  image.SetDirectionCosines(cosines);
  const double spacing[3] = {s.pixel_spacing_x, s.pixel_spacing_y, 1.0};
  image.SetSpacing(spacing);
  image.SetSlope(s.slope);
  image.SetIntercept(s.intercept);
  std::vector<std::int16_t> pixels(std::size_t(s.columns * s.rows));
  for (int j = 0; j < s.rows; ++j) {
    for (int i = 0; i < s.columns; ++i) pixels[std::size_t(j * s.columns + i)] = stored_value(i, j, s.k);
  }
  gdcm::DataElement pixel_data(gdcm::Tag(0x7fe0, 0x0010));
  pixel_data.SetByteValue(reinterpret_cast<const char*>(pixels.data()), std::uint32_t(pixels.size() * 2));
  image.SetDataElement(pixel_data);

  gdcm::DataSet& ds = writer.GetFile().GetDataSet();
  const char* sop_class = gdcm::MediaStorage::GetMSString(gdcm::MediaStorage::CTImageStorage);
  gdcm::DataElement ms(gdcm::Tag(0x0008, 0x0016));
  ms.SetByteValue(sop_class, std::uint32_t(std::strlen(sop_class)));
  ms.SetVR(gdcm::VR::UI);
  ds.Replace(ms);
  gdcm::Attribute<0x0020, 0x000e> series;
  series.SetValue(s.series_uid.c_str());
  ds.Replace(series.GetAsDataElement());
  gdcm::Attribute<0x0008, 0x0060> modality;
  modality.SetValue("CT");
  ds.Replace(modality.GetAsDataElement());
  writer.SetFileName(path.string().c_str());
  ASSERT_TRUE(writer.Write()) << path;
}

}  // namespace

TEST(Dicom, SyntheticSeriesSortedRescaledAndOriented) {
  const auto dir = test::scratch_dir("dicom");
  // An oblique series: rows along (cos a, sin a, 0), columns along z, slices stepping 2.5 mm along the normal,
  // written in shuffled order, plus a smaller second series and a text file to ignore.
  const double a = 0.3;
  const Vec3 row(std::cos(a), std::sin(a), 0.0), col(0.0, 0.0, -1.0);
  const Vec3 normal = row.cross(col);
  const Vec3 p0(-80.0, 40.0, 100.0);
  const int order[5] = {3, 0, 4, 1, 2};
  for (int n = 0; n < 5; ++n) {
    SliceSpec s;
    s.k = order[n];
    s.position = p0 + 2.5 * s.k * normal;
    s.row_direction = row;
    s.column_direction = col;
    s.series_uid = "1.2.826.0.1.3680043.2.1125.1.1";
    write_slice(dir / ("img" + std::to_string(n) + ".dcm"), s);
  }
  for (int n = 0; n < 2; ++n) {
    SliceSpec s;
    s.k = n;
    s.position = Vec3(0, 0, 3.0 * n);
    s.series_uid = "1.2.826.0.1.3680043.2.1125.1.2";
    s.slope = 2.0;
    s.intercept = 0.0;
    write_slice(dir / ("other" + std::to_string(n) + ".dcm"), s);
  }
  write_file_atomic(dir / "README.txt", "not DICOM");

  const std::vector<DicomSeriesInfo> series = list_dicom_series(dir);
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].files.size(), 5u);

  const ScalarGrid g = read_volume(dir);
  ASSERT_EQ(g.nx, 6);
  ASSERT_EQ(g.ny, 4);
  ASSERT_EQ(g.nz, 5);
  EXPECT_NEAR(g.spacing.x(), 0.5, 1e-9);
  EXPECT_NEAR(g.spacing.y(), 0.75, 1e-9);
  EXPECT_NEAR(g.spacing.z(), 2.5, 1e-6);
  EXPECT_LT((g.origin - p0).norm(), 1e-4);
  EXPECT_LT((g.direction.col(0) - row).norm(), 1e-5);
  EXPECT_LT((g.direction.col(1) - col).norm(), 1e-5);
  EXPECT_LT((g.direction.col(2) - normal).norm(), 1e-5);
  for (int k = 0; k < 5; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 6; ++i) ASSERT_EQ(g.at(i, j, k), float(stored_value(i, j, k) - 1024)) << i << j << k;
    }
  }
  const ScalarGrid other = read_dicom_series(dir, "1.2.826.0.1.3680043.2.1125.1.2");
  ASSERT_EQ(other.nz, 2);
  EXPECT_EQ(other.at(1, 2, 1), 2.0f * float(stored_value(1, 2, 1)));
  EXPECT_NEAR(other.spacing.z(), 3.0, 1e-6);
  EXPECT_THROW(read_dicom_series(dir, "9.9.9"), InputError);
}

TEST(Dicom, InconsistentSlicesAreInputErrors) {
  const auto dir = test::scratch_dir("dicom_bad");
  SliceSpec s;
  s.series_uid = "1.2.3.4";
  write_slice(dir / "a.dcm", s);
  s.position.z() = 2.0;
  s.columns = 7;  // a different size
  write_slice(dir / "b.dcm", s);
  EXPECT_THROW(read_dicom_series(dir), InputError);
  s.columns = 6;
  write_slice(dir / "b.dcm", s);
  s.position.z() = 2.0;  // same position as b
  write_slice(dir / "c.dcm", s);
  EXPECT_THROW(read_dicom_series(dir), InputError);
  s.position.z() = 10.0;  // a gap: slices missing
  write_slice(dir / "c.dcm", s);
  EXPECT_THROW(read_dicom_series(dir), InputError);
  const auto empty = test::scratch_dir("dicom_empty");
  write_file_atomic(empty / "x.dcm", std::string(200, '\0'));
  EXPECT_THROW(read_dicom_series(empty), InputError);
}
