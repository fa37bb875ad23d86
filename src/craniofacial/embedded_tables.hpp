#pragma once
/// Data files compiled into the library (generated at build time from data/tissue_depth/*.csv by
/// embed_files.cmake), so the binary needs no data path.

#include <string_view>
#include <vector>

namespace forensim {

/// One embedded file: its stem ("ttable_2023") and its bytes.
struct EmbeddedFile {
  std::string_view name;
  std::string_view text;
};

/// The built-in tissue-depth tables, sorted by name.
const std::vector<EmbeddedFile>& embedded_tissue_depth_tables();

}  // namespace forensim
