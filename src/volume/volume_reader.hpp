#pragma once
/// One entry point for loading any supported volume.

#include <filesystem>

#include "volume/scalar_grid.hpp"

namespace forensim {

/// Reads a volume, choosing the reader by extension and then by content: .nrrd/.nhdr (or a file starting with
/// "NRRD000") -> read_nrrd; .mhd/.mha (or a header starting with a MetaImage key) -> read_metaimage; a folder, or a
/// .dcm file or a file with "DICM" at byte 128 (its folder is read) -> read_dicom_series (largest series); a
/// .tif/.tiff file -> read_image_stack of its pages with 1 mm spacing. Throws InputError for an unknown format,
/// IoError when the path does not exist.
ScalarGrid read_volume(const std::filesystem::path& path);

}  // namespace forensim
