#pragma once
/// Where forensim finds shared real data (CT volumes, scans) that is never copied into the repository.

#include <filesystem>

namespace forensim {

/// $FORENSIM_DATA_DIR when set and not empty, else the folder configured at build time (../shared/data
/// beside the source tree). The folder need not exist: callers check for the items they use.
std::filesystem::path shared_data_dir();

}  // namespace forensim
