#pragma once
/// Volumes stored as a stack of 2-D greyscale slice images (TIFF or PNG), as microscopes, micro-CT scanners and
/// many online archives export them. The images carry no geometry, so the caller gives the voxel spacing.

#include <filesystem>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

/// Reads slices in the given order (slice n = k index n) into a grid with the given spacing (mm along i = image
/// columns, j = image rows from the top, k = slices), origin 0 and identity direction. Each file is a single-sample
/// 8- or 16-bit greyscale TIFF (libtiff; strips or tiles, any compression libtiff decodes; a multi-page TIFF adds one
/// slice per page) or PNG (libpng; 16-bit values are read as stored). Values are the stored integers as floats.
/// Throws InputError naming the file when it is not such an image or its size differs from the first slice's,
/// or the spacing is not positive; IoError when a file cannot be opened.
ScalarGrid read_image_stack(const std::vector<std::filesystem::path>& files, const Vec3& spacing_mm);

/// Files in `folder` whose names match `pattern` (a glob with '*' for any run of characters and '?' for one
/// character, e.g. "slice_*.tif"), sorted naturally (digit runs compare as numbers: slice_2 before slice_10).
std::vector<std::filesystem::path> list_matching_files(const std::filesystem::path& folder, const std::string& pattern);

/// read_image_stack(list_matching_files(folder, pattern), spacing_mm); InputError when nothing matches.
ScalarGrid read_image_stack(const std::filesystem::path& folder, const std::string& pattern, const Vec3& spacing_mm);

}  // namespace forensim
