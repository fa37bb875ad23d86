#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/metaimage_reader.hpp"
#include "volume/nrrd_reader.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

// Reads every mutation of `original` written as `name`; each must load or fail with a forensim::Error (under the
// sanitizer build this also checks for out-of-bounds reads and leaks).
void read_mutations(const std::filesystem::path& dir, const std::string& name, const std::string& original,
                    unsigned seed) {
  std::mt19937 rng(seed);
  const char* tokens[] = {"-1", "0", "99999999999", "nan", "LIST", "%d 1 9 1", "\n", ":", "=", "(", ")", "gzip", "raw"};
  int accepted = 0;
  for (int round = 0; round < 150; ++round) {
    std::string bytes = original;
    const int edits = 1 + int(rng() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const std::size_t at = rng() % bytes.size();
      switch (rng() % 4) {
        case 0:
          bytes[at] = static_cast<char>(rng() % 256);
          break;
        case 1:
          bytes.erase(at, 1 + rng() % 8);
          break;
        case 2:
          bytes.insert(at, tokens[rng() % std::size(tokens)]);
          break;
        default:
          bytes.resize(at);
          break;
      }
    }
    std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << bytes;  // no fsync: scratch data
    try {
      read_volume(dir / name);
      ++accepted;
    } catch (const forensim::Error&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "round " << round << ": not a forensim::Error: " << e.what();
    }
  }
  ::testing::Test::RecordProperty("accepted_" + name, accepted);
}

}  // namespace

TEST(VolumeMutations, MutatedHeadersAndDataFailCleanly) {
  const auto dir = test::scratch_dir("mutations");
  ScalarGrid g = ScalarGrid::filled(4, 3, 2);
  for (std::size_t i = 0; i < g.values.size(); ++i) g.values[i] = float(i);
  write_nrrd(dir / "a.nrrd", g, false);
  write_nrrd(dir / "z.nrrd", g, true);
  write_metaimage(dir / "m.mha", g, false);
  write_metaimage(dir / "c.mha", g, true);
  unsigned seed = 1;
  for (const char* name : {"a.nrrd", "z.nrrd", "m.mha", "c.mha"}) {
    read_mutations(dir, std::string("mut_") + name, read_file(dir / name), seed++);
  }
  // Detached headers pointing at the (intact) data files.
  write_nrrd(dir / "d.nhdr", g, true);
  write_metaimage(dir / "d.mhd", g, true);
  read_mutations(dir, "mut_d.nhdr", read_file(dir / "d.nhdr"), seed++);
  read_mutations(dir, "mut_d.mhd", read_file(dir / "d.mhd"), seed++);
}
