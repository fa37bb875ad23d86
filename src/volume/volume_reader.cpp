#include "volume/volume_reader.hpp"

#include <fstream>

#include "core/error.hpp"
#include "volume/dicom_reader.hpp"
#include "volume/header_text.hpp"
#include "volume/image_stack_reader.hpp"
#include "volume/metaimage_reader.hpp"
#include "volume/nrrd_reader.hpp"

namespace forensim {

ScalarGrid read_volume(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return read_dicom_series(path);
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string(), "does not exist");
  const std::string ext = to_lower(path.extension().string());
  if (ext == ".nrrd" || ext == ".nhdr") return read_nrrd(path);
  if (ext == ".mhd" || ext == ".mha") return read_metaimage(path);
  if (ext == ".dcm") return read_dicom_series(path.parent_path());
  if (ext == ".tif" || ext == ".tiff") return read_image_stack(std::vector<std::filesystem::path>{path}, Vec3::Ones());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading");
  std::string head(132, '\0');
  in.read(head.data(), 132);
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.rfind("NRRD000", 0) == 0) return read_nrrd(path);
  if (head.size() == 132 && head.compare(128, 4, "DICM") == 0) return read_dicom_series(path.parent_path());
  const std::string low = to_lower(head);
  for (const char* key : {"objecttype", "ndims"}) {
    if (low.rfind(key, 0) == 0) return read_metaimage(path);
  }
  throw InputError(path.string(), "byte 0", "unknown volume format (expected NRRD, MetaImage, DICOM or TIFF)");
}

}  // namespace forensim
