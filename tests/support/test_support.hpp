#pragma once
/// Helpers shared by forensim's tests: where the shared data and the test corpus live, and scratch folders.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace forensim::test {

/// Folder of shared real data: $FORENSIM_DATA_DIR, else the configured ../shared/data.
std::filesystem::path data_dir();
/// Path of a data item (e.g. "ct-head-headsq/quarter.nhdr"), or an empty path when it is absent.
std::filesystem::path data_path(const std::string& relative);
/// The repository's tests/ folder (bad-input corpus, golden images).
std::filesystem::path tests_dir();
/// A fresh, empty scratch folder for one test, removed at process exit if empty.
std::filesystem::path scratch_dir(const std::string& name);

}  // namespace forensim::test

/// Skips the current test with a clear message when a shared data item is absent; else binds `var` to it.
#define FORENSIM_REQUIRE_DATA(var, relative)                                                              \
  const std::filesystem::path var = ::forensim::test::data_path(relative);                                \
  if (var.empty()) {                                                                                      \
    GTEST_SKIP() << "shared data '" << (relative) << "' not found under " << ::forensim::test::data_dir() \
                 << " (set FORENSIM_DATA_DIR to run this test)";                                          \
  }
