#pragma once
/// DICOM CT/MR series (a folder of slice files, as scanners and PACS exports deliver them), read through GDCM.

#include <filesystem>
#include <string>
#include <vector>

#include "volume/scalar_grid.hpp"

namespace forensim {

/// One image series found in a folder.
struct DicomSeriesInfo {
  std::string series_instance_uid;  ///< (0020,000E)
  std::vector<std::filesystem::path> files;
};

/// Lists the image series among the regular files of `folder` (not recursive; files GDCM cannot parse as DICOM
/// images, such as DICOMDIR or notes, are skipped), largest series first. Throws IoError when the folder cannot be
/// listed.
std::vector<DicomSeriesInfo> list_dicom_series(const std::filesystem::path& folder);

/// Reads one series of a folder into a grid in LPS mm (DICOM's patient coordinates are LPS) with rescaled values
/// (RescaleSlope * stored + RescaleIntercept, per slice: Hounsfield units for CT). `series_instance_uid` picks the
/// series; empty = the series with the most slices. Slices are sorted by ImagePositionPatient projected on the slice
/// normal (row direction x column direction from ImageOrientationPatient); the slice spacing is the mean gap
/// between neighbouring positions; the in-plane spacing is PixelSpacing; the grid's direction columns are the row
/// direction, column direction and normal; its origin is the first slice's ImagePositionPatient. A series that is one
/// multi-frame file is read with GDCM's 3-D geometry. Throws InputError naming the folder or file when no series is
/// found, the requested UID is absent, slices differ in size, orientation or pixel type, two slices share a position,
/// gaps differ by more than 10 %, or pixels are not single-sample greyscale.
ScalarGrid read_dicom_series(const std::filesystem::path& folder, const std::string& series_instance_uid = "");

}  // namespace forensim
