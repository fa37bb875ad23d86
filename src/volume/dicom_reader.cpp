#include "volume/dicom_reader.hpp"

#include <gdcmImage.h>
#include <gdcmImageHelper.h>
#include <gdcmImageReader.h>
#include <gdcmPixelFormat.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "volume/voxel_data.hpp"

namespace forensim {
namespace {

struct SliceHeader {
  std::filesystem::path file;
  std::string uid;
};

std::string element_string(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (bv == nullptr) return {};
  std::string s(bv->GetPointer(), bv->GetLength());
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return s;
}

void quiet_gdcm() {
  gdcm::Trace::DebugOff();
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
}

VoxelType voxel_type_of(const gdcm::PixelFormat& pf, const std::string& source) {
  switch (pf.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
      return VoxelType::uint8;
    case gdcm::PixelFormat::INT8:
      return VoxelType::int8;
    case gdcm::PixelFormat::UINT16:
      return VoxelType::uint16;
    case gdcm::PixelFormat::INT16:
      return VoxelType::int16;
    case gdcm::PixelFormat::UINT32:
      return VoxelType::uint32;
    case gdcm::PixelFormat::INT32:
      return VoxelType::int32;
    case gdcm::PixelFormat::FLOAT32:
      return VoxelType::float32;
    case gdcm::PixelFormat::FLOAT64:
      return VoxelType::float64;
    default:
      throw InputError(source, "(0028,0100) BitsAllocated",
                       std::string("unsupported pixel format ") + pf.GetScalarTypeAsString());
  }
}

struct SliceImage {
  std::filesystem::path file;
  unsigned dims[3] = {0, 0, 1};
  Vec3 origin = Vec3::Zero();
  Vec3 row = Vec3::UnitX(), col = Vec3::UnitY();
  Vec3 spacing = Vec3::Ones();
  double slope = 1.0, intercept = 0.0;
  std::vector<float> values;
};

SliceImage read_slice(const std::filesystem::path& file) {
  const std::string src = file.string();
  gdcm::ImageReader reader;
  reader.SetFileName(src.c_str());
  if (!reader.Read()) throw InputError(src, "", "GDCM cannot read this file as a DICOM image");
  const gdcm::Image& image = reader.GetImage();
  SliceImage s;
  s.file = file;
  const unsigned* dims = image.GetDimensions();
  s.dims[0] = dims[0];
  s.dims[1] = dims[1];
  s.dims[2] = image.GetNumberOfDimensions() >= 3 ? dims[2] : 1;
  const std::int64_t sizes[3] = {s.dims[0], s.dims[1], s.dims[2]};
  const std::uint64_t count = checked_voxel_count(sizes, src, "(0028,0010) Rows / (0028,0011) Columns");
  const gdcm::PixelFormat pf = image.GetPixelFormat();
  require_input(pf.GetSamplesPerPixel() == 1, src, "(0028,0002) SamplesPerPixel",
                "has " + std::to_string(pf.GetSamplesPerPixel()) + " samples per pixel; only greyscale is supported");
  const VoxelType type = voxel_type_of(pf, src);
  const std::uint64_t bytes = count * voxel_type_size(type);
  const unsigned long length = image.GetBufferLength();
  require_input(length == bytes, src, "(7FE0,0010) PixelData",
                "expected " + std::to_string(bytes) + " bytes of pixel data, found " + std::to_string(length));
  // Check the declared size against the pixel data really present before allocating: native pixel data must hold
  // every byte; compressed (encapsulated) data is bounded by a generous ratio to the file's size.
  if (const gdcm::ByteValue* bv = image.GetDataElement().GetByteValue(); bv != nullptr) {
    require_input(
        bv->GetLength() >= bytes, src, "(7FE0,0010) PixelData",
        "expected " + std::to_string(bytes) + " bytes of pixel data, found " + std::to_string(bv->GetLength()));
  } else {
    std::error_code ec;
    const std::uint64_t file_size = std::filesystem::file_size(file, ec);
    require_input(
        !ec && bytes <= file_size * 2000 + (std::uint64_t{1} << 20), src, "(7FE0,0010) PixelData",
        std::to_string(bytes) + " bytes of pixels cannot come from a file of " + std::to_string(file_size) + " bytes");
  }
  std::vector<char> buffer(length);
  if (!image.GetBuffer(buffer.data())) throw InputError(src, "(7FE0,0010) PixelData", "cannot decode the pixel data");
  s.values.resize(count);
  decode_voxels(reinterpret_cast<const unsigned char*>(buffer.data()), count, type, false, s.values.data());
  // GDCM's Image keeps only NumberOfDimensions origin/spacing components; read the full values from the file.
  const std::vector<double> o = gdcm::ImageHelper::GetOriginValue(reader.GetFile());
  const std::vector<double> dc = gdcm::ImageHelper::GetDirectionCosinesValue(reader.GetFile());
  const std::vector<double> sp = gdcm::ImageHelper::GetSpacingValue(reader.GetFile());
  require_input(o.size() >= 3, src, "(0020,0032) ImagePositionPatient", "needs three numbers");
  require_input(dc.size() >= 6, src, "(0020,0037) ImageOrientationPatient", "needs six numbers");
  require_input(sp.size() >= 2, src, "(0028,0030) PixelSpacing", "needs two numbers");
  s.origin = Vec3(o[0], o[1], o[2]);
  s.row = Vec3(dc[0], dc[1], dc[2]);
  s.col = Vec3(dc[3], dc[4], dc[5]);
  s.spacing = Vec3(sp[0], sp[1], s.dims[2] > 1 && sp.size() >= 3 ? sp[2] : 1.0);
  s.slope = image.GetSlope();
  s.intercept = image.GetIntercept();
  require_input(s.origin.allFinite(), src, "(0020,0032) ImagePositionPatient", "is not finite");
  require_input(s.row.allFinite() && s.col.allFinite() && s.row.norm() > 0.5 && s.col.norm() > 0.5 &&
                    std::abs(s.row.normalized().dot(s.col.normalized())) < 1e-3,
                src, "(0020,0037) ImageOrientationPatient", "is not two orthogonal unit vectors");
  require_input(s.spacing.allFinite() && (s.spacing.array() > 0.0).all(), src, "(0028,0030) PixelSpacing",
                "is not positive");
  require_input(std::isfinite(s.slope) && std::isfinite(s.intercept) && s.slope != 0.0, src, "(0028,1053) RescaleSlope",
                "slope or intercept is not finite and non-zero");
  s.row.normalize();
  s.col.normalize();
  return s;
}

}  // namespace

std::vector<DicomSeriesInfo> list_dicom_series(const std::filesystem::path& folder) {
  quiet_gdcm();
  std::error_code ec;
  std::filesystem::directory_iterator it(folder, ec);
  if (ec) throw IoError(folder.string(), "cannot list the folder: " + ec.message());
  std::vector<std::filesystem::path> files;
  for (const auto& entry : it) {
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::map<std::string, DicomSeriesInfo> series;
  for (const auto& file : files) {
    gdcm::Reader reader;
    reader.SetFileName(file.string().c_str());
    try {
      if (!reader.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010))) continue;
    } catch (const std::exception&) {
      continue;
    }
    const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
    if (!ds.FindDataElement(gdcm::Tag(0x0028, 0x0010))) continue;  // no Rows: not an image
    const std::string uid = element_string(ds, gdcm::Tag(0x0020, 0x000e));
    DicomSeriesInfo& info = series[uid];
    info.series_instance_uid = uid;
    info.files.push_back(file);
  }
  std::vector<DicomSeriesInfo> out;
  for (auto& [uid, info] : series) out.push_back(std::move(info));
  std::stable_sort(out.begin(), out.end(),
                   [](const DicomSeriesInfo& a, const DicomSeriesInfo& b) { return a.files.size() > b.files.size(); });
  return out;
}

ScalarGrid read_dicom_series(const std::filesystem::path& folder, const std::string& series_instance_uid) {
  const std::string src = folder.string();
  const std::vector<DicomSeriesInfo> all = list_dicom_series(folder);
  require_input(!all.empty(), src, "", "no DICOM image series found in the folder");
  const DicomSeriesInfo* chosen = &all.front();
  if (!series_instance_uid.empty()) {
    chosen = nullptr;
    for (const auto& s : all) {
      if (s.series_instance_uid == series_instance_uid) chosen = &s;
    }
    require_input(chosen != nullptr, src, "(0020,000E) SeriesInstanceUID",
                  "no series with UID '" + series_instance_uid + "' (found " + std::to_string(all.size()) + ")");
  }

  std::vector<SliceImage> slices;
  try {
    for (const auto& file : chosen->files) slices.push_back(read_slice(file));
  } catch (const forensim::Error&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(src, "", std::string("GDCM failed: ") + e.what());
  }

  ScalarGrid grid;
  if (slices.size() == 1 && slices[0].dims[2] > 1) {
    SliceImage& s = slices[0];
    grid.nx = int(s.dims[0]);
    grid.ny = int(s.dims[1]);
    grid.nz = int(s.dims[2]);
    grid.spacing = s.spacing;
    grid.origin = s.origin;
    grid.direction.col(0) = s.row;
    grid.direction.col(1) = s.col;
    grid.direction.col(2) = s.row.cross(s.col);
    grid.values = std::move(s.values);
    for (float& v : grid.values) v = static_cast<float>(v * s.slope + s.intercept);
    grid.validate(src);
    return grid;
  }
  const SliceImage& first = slices.front();
  const Vec3 normal = first.row.cross(first.col);
  for (const SliceImage& s : slices) {
    const std::string f = s.file.string();
    require_input(s.dims[2] == 1, f, "(0028,0008) NumberOfFrames", "a multi-frame file in a series of slices");
    require_input(s.dims[0] == first.dims[0] && s.dims[1] == first.dims[1], f, "(0028,0010) Rows / (0028,0011) Columns",
                  std::to_string(s.dims[0]) + " x " + std::to_string(s.dims[1]) + " differs from " +
                      std::to_string(first.dims[0]) + " x " + std::to_string(first.dims[1]) + " of " +
                      first.file.filename().string());
    require_input((s.row - first.row).norm() < 1e-3 && (s.col - first.col).norm() < 1e-3, f,
                  "(0020,0037) ImageOrientationPatient", "differs from the other slices");
    require_input((s.spacing.head<2>() - first.spacing.head<2>()).norm() < 1e-4 * first.spacing.head<2>().norm(), f,
                  "(0028,0030) PixelSpacing", "differs from the other slices");
  }
  std::stable_sort(slices.begin(), slices.end(), [&](const SliceImage& a, const SliceImage& b) {
    return a.origin.dot(normal) < b.origin.dot(normal);
  });
  double slice_spacing = 1.0;
  if (slices.size() > 1) {
    std::vector<double> gaps;
    for (std::size_t i = 1; i < slices.size(); ++i) {
      gaps.push_back((slices[i].origin - slices[i - 1].origin).dot(normal));
      require_input(gaps.back() > 1e-4, slices[i].file.string(), "(0020,0032) ImagePositionPatient",
                    "has the same position as " + slices[i - 1].file.filename().string());
    }
    slice_spacing = (slices.back().origin - slices.front().origin).dot(normal) / double(slices.size() - 1);
    for (std::size_t i = 0; i < gaps.size(); ++i) {
      require_input(std::abs(gaps[i] - slice_spacing) <= 0.1 * slice_spacing, slices[i + 1].file.string(),
                    "(0020,0032) ImagePositionPatient",
                    "slice gap " + std::to_string(gaps[i]) + " mm differs from the mean " +
                        std::to_string(slice_spacing) + " mm (missing slice?)");
    }
  }
  const std::int64_t sizes[3] = {first.dims[0], first.dims[1], std::int64_t(slices.size())};
  checked_voxel_count(sizes, src, "slices");
  grid.nx = int(first.dims[0]);
  grid.ny = int(first.dims[1]);
  grid.nz = int(slices.size());
  grid.spacing = Vec3(first.spacing[0], first.spacing[1], slice_spacing);
  grid.origin = slices.front().origin;
  grid.direction.col(0) = first.row;
  grid.direction.col(1) = first.col;
  grid.direction.col(2) = normal.normalized();
  grid.values.resize(grid.voxel_count());
  const std::size_t per_slice = std::size_t(grid.nx) * std::size_t(grid.ny);
  for (std::size_t k = 0; k < slices.size(); ++k) {
    const SliceImage& s = slices[k];
    for (std::size_t i = 0; i < per_slice; ++i) {
      grid.values[k * per_slice + i] = static_cast<float>(s.values[i] * s.slope + s.intercept);
    }
  }
  grid.validate(src);
  return grid;
}

}  // namespace forensim
