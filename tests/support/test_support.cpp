#include "support/test_support.hpp"

#include <system_error>

#include "core/data_dir.hpp"
#include "forensim/config.hpp"

namespace forensim::test {

std::filesystem::path data_dir() {
  return shared_data_dir();
}

std::filesystem::path data_path(const std::string& relative) {
  const std::filesystem::path p = data_dir() / relative;
  std::error_code ec;
  return std::filesystem::exists(p, ec) ? p : std::filesystem::path();
}

std::filesystem::path tests_dir() {
  return std::filesystem::path(FORENSIM_SOURCE_DIR) / "tests";
}

std::filesystem::path scratch_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string folder = name;
  if (info != nullptr) folder = std::string(info->test_suite_name()) + "." + info->name() + "." + name;
  const std::filesystem::path p = std::filesystem::temp_directory_path() / "forensim-tests" / folder;
  std::error_code ec;
  std::filesystem::remove_all(p, ec);
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace forensim::test
