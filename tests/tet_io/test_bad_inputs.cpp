// Hostile and broken inputs: every file of tests/corpus/tet_io must raise InputError (never crash, hang or
// allocate from an unchecked count), and generated truncations and byte mutations of valid files must either
// read or raise InputError. Run under AddressSanitizer in CI, so an out-of-bounds read fails here too.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/error.hpp"
#include "support/test_support.hpp"
#include "tet_io/gmsh_io.hpp"
#include "tet_io/pvd_writer.hpp"
#include "tet_io/sample_tet_mesh.hpp"
#include "tet_io/tetgen_io.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"

using namespace forensim;

namespace {

/// Reads `path` with the reader its extension names.
void read_any(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".msh") {
    read_gmsh(path);
  } else if (ext == ".node" || ext == ".ele") {
    read_tetgen(path);
  } else if (ext == ".vtu") {
    read_vtu(path);
  } else if (ext == ".pvd") {
    read_pvd(path);
  } else {
    FAIL() << "no reader for " << path;
  }
}

/// Reads `path`; returns "" when it reads, the problem when it raises InputError; fails on anything else.
std::string file_outcome(const std::filesystem::path& path) {
  try {
    read_any(path);
    return "";
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": not an InputError: " << e.what();
    return e.what();
  }
}

/// A valid file the writers made, in memory; TetGen files carry their companion (.ele for .node and back).
struct Sample {
  std::string name;
  std::string bytes;
  std::string companion;
};

std::vector<Sample> valid_samples() {
  const auto dir = test::scratch_dir("valid");
  const TetMesh mesh = test::sample_tet_mesh(1, 1, 1);
  write_gmsh(dir / "ascii.msh", mesh);
  write_gmsh(dir / "binary.msh", mesh, true);
  write_tetgen(dir / "mesh", mesh);
  std::vector<Sample> samples = {{"ascii.msh", test::slurp(dir / "ascii.msh"), ""},
                                 {"binary.msh", test::slurp(dir / "binary.msh"), ""},
                                 {"mesh.node", test::slurp(dir / "mesh.node"), test::slurp(dir / "mesh.ele")},
                                 {"mesh.ele", test::slurp(dir / "mesh.ele"), test::slurp(dir / "mesh.node")}};
  const std::pair<VtuEncoding, bool> kinds[] = {{VtuEncoding::ascii, false},
                                                {VtuEncoding::inline_base64, false},
                                                {VtuEncoding::inline_base64, true},
                                                {VtuEncoding::appended_raw, false},
                                                {VtuEncoding::appended_raw, true}};
  int i = 0;
  for (const auto& [encoding, compress] : kinds) {
    VtuOptions o;
    o.encoding = encoding;
    o.compress = compress;
    const std::string name = std::string("v") + std::to_string(i++) + ".vtu";
    write_vtu(dir / name, mesh, o);
    samples.push_back({name, test::slurp(dir / name), ""});
  }
  // VTK's default layout (base64 appended data), which forensim reads but does not write.
  for (const char* name : {"vtk_appended_base64.vtu", "vtk_appended_base64_zlib_uint32.vtu"}) {
    samples.push_back({name, test::slurp(test::tests_dir() / "tet_io" / "foreign" / name), ""});
  }
  PvdSeries series(dir / "run.pvd");
  series.add(0.5, "v0.vtu");
  samples.push_back({"run.pvd", test::slurp(dir / "run.pvd"), ""});
  return samples;
}

/// Parses `bytes` as `sample`'s format; "" when it reads, the message when it raises InputError; fails the
/// test on any other exception.
std::string outcome(const Sample& sample, const std::string& bytes) {
  const std::string ext = std::filesystem::path(sample.name).extension().string();
  try {
    if (ext == ".msh") {
      parse_gmsh(bytes, sample.name);
    } else if (ext == ".node") {
      parse_tetgen(bytes, sample.companion, sample.name, "companion.ele");
    } else if (ext == ".ele") {
      parse_tetgen(sample.companion, bytes, "companion.node", sample.name);
    } else if (ext == ".vtu") {
      parse_vtu(bytes, sample.name);
    } else {
      parse_pvd(bytes, sample.name);
    }
    return "";
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << sample.name << ": not an InputError: " << e.what();
    return e.what();
  }
}

bool ends_with_section_end(std::string prefix) {
  while (!prefix.empty() && (prefix.back() == '\n' || prefix.back() == ' ')) prefix.pop_back();
  for (const char* end : {"$EndNodes", "$EndElements", "$EndNodeData", "$EndElementData"}) {
    const std::string e = end;
    if (prefix.size() >= e.size() && prefix.compare(prefix.size() - e.size(), e.size(), e) == 0) return true;
  }
  return false;
}

}  // namespace

TEST(BadInputs, EveryCorpusFileIsAnInputError) {
  const auto corpus = test::tests_dir() / "corpus" / "tet_io";
  ASSERT_TRUE(std::filesystem::is_directory(corpus)) << corpus;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const auto ext = entry.path().extension();
    if (ext == ".msh" || ext == ".node" || ext == ".vtu" || ext == ".pvd") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 80u);
  for (const auto& path : files) {
    const std::string problem = file_outcome(path);
    EXPECT_FALSE(problem.empty()) << path.filename() << " was accepted";
    // The message names the file.
    EXPECT_NE(problem.find(path.filename().replace_extension().string()), std::string::npos) << problem;
  }
}

TEST(BadInputs, TruncatedFilesReadOrRaiseInputError) {
  for (const Sample& sample : valid_samples()) {
    SCOPED_TRACE(sample.name);
    ASSERT_EQ(outcome(sample, sample.bytes), "");
    for (std::size_t n = 0; n < sample.bytes.size(); ++n) {
      const std::string prefix = sample.bytes.substr(0, n);
      const std::string problem = outcome(sample, prefix);
      // A Gmsh file cut anywhere but right after a complete mesh or data section is incomplete.
      if (sample.name == "binary.msh" && problem.empty()) {
        EXPECT_TRUE(ends_with_section_end(prefix)) << "accepted a cut at byte " << n;
      }
    }
  }
}

TEST(BadInputs, MutatedFilesReadOrRaiseInputError) {
  std::mt19937 random(20261122);
  const char replacements[] = {'0', '9', '-', ' ', '\n', '\0', '\xff', 'e', '.', '<', '"', '$', '_', 'A', '='};
  for (const Sample& sample : valid_samples()) {
    SCOPED_TRACE(sample.name);
    for (int trial = 0; trial < 1000; ++trial) {
      std::string changed = sample.bytes;
      const int edits = 1 + static_cast<int>(random() % 3);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = random() % changed.size();
        changed[at] = (random() % 2) ? replacements[random() % sizeof(replacements)] : static_cast<char>(random());
      }
      outcome(sample, changed);
    }
  }
}
