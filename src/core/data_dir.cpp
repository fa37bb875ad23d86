#include "core/data_dir.hpp"

#include <cstdlib>

#include "forensim/config.hpp"

namespace forensim {

std::filesystem::path shared_data_dir() {
  if (const char* env = std::getenv("FORENSIM_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return FORENSIM_DEFAULT_DATA_DIR;
}

}  // namespace forensim
