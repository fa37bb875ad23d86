#include <gtest/gtest.h>

#include <set>

#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

// Every header in tests/corpus/volume is hostile or broken; each must give an InputError that names the file,
// never a crash, a hang or a huge allocation.
TEST(VolumeCorpus, EveryFileIsAnInputError) {
  const auto dir = test::tests_dir() / "corpus" / "volume";
  const std::set<std::string> headers = {".nrrd", ".nhdr", ".mhd", ".mha", ".vol"};
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (headers.count(entry.path().extension().string()) == 0) continue;
    ++checked;
    try {
      read_volume(entry.path());
      ADD_FAILURE() << entry.path() << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(entry.path().filename().string()), std::string::npos)
          << "message does not name the file: " << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << " threw something else than InputError: " << e.what();
    }
  }
  EXPECT_GE(checked, 50);
}
