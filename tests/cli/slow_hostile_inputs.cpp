// Hostile inputs for every forensim subcommand (issue 29), not only for the readers. Each command, for each
// of its file-taking options, runs on every file of the matching bad-input corpus (tests/corpus/{mesh_io,
// volume,image,tet_io}), on the files of the other corpora (a mesh option given a volume or a picture), and
// on malformed files made here: a missing path, an empty file, a folder, garbage bytes, a constant volume, a
// NRRD declaring 100000^3 voxels, a GLB whose JSON chunk is 2^31 bytes long, JSON nested 100000 deep, ...
// Each output option is also pointed below a regular file, at a folder whose parent does not exist (for file
// outputs) and, unless running as root (root ignores permissions), into a read-only folder.
//
// Every (command, input) pair must end as a forensim error: no signal, no hang (a 60 s limit per run), an
// exit code of 2 (usage), 3 (input), 4 (job) or 5 (io) (core/error.hpp), a message that says forensim and
// names the bad input, and nothing left at the requested output path (no half-written output). Each test
// runs all its pairs, reports every failing one with the command line that reproduces it, and prints
// `hostile inputs: N (command, input) pairs, S signals, H hangs`.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using forensim::test::run_cli_timed;

namespace {

constexpr double k_time_limit_s = 60.0;

/// One run of forensim on a hostile input.
struct HostileCase {
  std::vector<std::string> arguments;
  std::string names;  ///< text the error message must contain (the bad input's file name); empty: none
  fs::path output;    ///< the requested output, which must not exist after the run; empty: none
};

struct Tally {
  std::size_t pairs = 0, signals = 0, hangs = 0, failures = 0;
  double seconds = 0.0;
};

Tally& process_tally() {
  static Tally tally;
  return tally;
}

/// The pair count of the whole process, printed once its tests have run.
class TallyPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    const Tally& t = process_tally();
    if (t.pairs == 0) return;
    std::printf("hostile inputs: %zu (command, input) pairs, %zu signals, %zu hangs, %zu other failures (%.1f s)\n",
                t.pairs, t.signals, t.hangs, t.failures, t.seconds);
  }
};
[[maybe_unused]] auto* const tally_printer = ::testing::AddGlobalTestEnvironment(new TallyPrinter);

std::string shell_quoted(const std::string& word) {
  if (!word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+") ==
          std::string::npos) {
    return word;
  }
  std::string quoted = "'";
  for (char c : word) {
    if (c == '\'') {
      quoted.append("'\\''");
    } else {
      quoted.push_back(c);
    }
  }
  quoted.push_back('\'');
  return quoted;
}

std::string command_line(const std::vector<std::string>& arguments) {
  std::string line = "forensim";
  for (const auto& a : arguments) {
    line.push_back(' ');
    line.append(shell_quoted(a));
  }
  return line;
}

/// The last `n` bytes of a run's output, for a failure message.
std::string tail(const std::string& text, std::size_t n = 600) {
  return text.size() <= n ? text : "..." + text.substr(text.size() - n);
}

/// Runs every case and fails the current test once, listing every pair that did not end as a forensim error.
void run_hostile(const std::string& group, const std::vector<HostileCase>& cases) {
  Tally tally;
  std::string failures;
  std::vector<std::pair<double, std::string>> slowest;  // (seconds, command line) of the slowest runs
  for (const HostileCase& c : cases) {
    std::error_code ec;
    const bool output_existed = !c.output.empty() && fs::exists(c.output, ec);
    const auto r = run_cli_timed(c.arguments, k_time_limit_s);
    ++tally.pairs;
    tally.seconds += r.seconds;
    slowest.emplace_back(r.seconds, command_line(c.arguments));
    std::string problem;
    if (r.exec_errno != 0) {
      problem = std::string("forensim could not be started: ") + std::strerror(r.exec_errno);
    } else if (r.signal != 0) {
      ++tally.signals;
      problem = "killed by signal " + std::to_string(r.signal);
    } else if (r.timed_out) {
      ++tally.hangs;
      problem = "still running after " + std::to_string(static_cast<int>(k_time_limit_s)) + " s";
    } else if (r.exit_code < 2 || r.exit_code > 5) {
      problem = "exit code " + std::to_string(r.exit_code) + " (a forensim error is 2 to 5)";
    } else if (r.exit_code != 2 && r.output.find("forensim") == std::string::npos) {
      problem = "the message does not say forensim";  // (usage errors are CLI11's: they name the option)
    } else if (!c.names.empty() && r.output.find(c.names) == std::string::npos) {
      problem = "the message does not name '" + c.names + "'";
    } else if (!output_existed && !c.output.empty() && fs::exists(c.output, ec)) {
      problem = "left " + c.output.string() + " behind";
    }
    // Outputs are requested in folders that start empty; whatever the run left there is removed for the next.
    if (!c.output.empty() && !output_existed) fs::remove_all(c.output, ec);
    if (!problem.empty()) {
      ++tally.failures;
      failures += "\n  " + command_line(c.arguments) + "\n    " + problem + " after " +
                  std::to_string(r.seconds).substr(0, 5) + " s; output:\n    " + tail(r.output) + "\n";
    }
  }
  Tally& total = process_tally();
  total.pairs += tally.pairs;
  total.signals += tally.signals;
  total.hangs += tally.hangs;
  total.failures += tally.failures;
  total.seconds += tally.seconds;
  std::printf("hostile inputs (%s): %zu (command, input) pairs, %zu signals, %zu hangs, %zu other failures (%.1f s)\n",
              group.c_str(), tally.pairs, tally.signals, tally.hangs, tally.failures, tally.seconds);
  const std::size_t shown = std::min<std::size_t>(3, slowest.size());
  std::partial_sort(slowest.begin(), slowest.begin() + static_cast<std::ptrdiff_t>(shown), slowest.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; i < shown; ++i)
    std::printf("  slowest: %.2f s  %s\n", slowest[i].first, slowest[i].second.c_str());
  ::testing::Test::RecordProperty("pairs", static_cast<int>(tally.pairs));
  ::testing::Test::RecordProperty("signals", static_cast<int>(tally.signals));
  ::testing::Test::RecordProperty("hangs", static_cast<int>(tally.hangs));
  EXPECT_TRUE(failures.empty()) << tally.failures << " of " << tally.pairs << " " << group
                                << " runs did not end as a forensim error:" << failures;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// `n` bytes from a fixed-seed generator: the same garbage on every run.
std::string garbage_bytes(std::size_t n, std::uint32_t seed) {
  std::string bytes(n, '\0');
  std::uint32_t x = seed;
  for (char& b : bytes) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<char>(x >> 24);
  }
  return bytes;
}

/// A closed cube (mm) as an OBJ: a good input beside the hostile one.
std::string cube_obj(double size) {
  const std::string s = std::to_string(size);
  return "v 0 0 0\nv " + s + " 0 0\nv " + s + " " + s + " 0\nv 0 " + s + " 0\nv 0 0 " + s + "\nv " + s + " 0 " + s +
         "\nv " + s + " " + s + " " + s + "\nv 0 " + s + " " + s +
         "\nf 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 "
         "8\n";
}

/// A raw little-endian NRRD of shorts, `nx ny nz` voxels declared, `data` following the header.
std::string nrrd_header(const std::string& sizes) {
  return "NRRD0004\ntype: short\ndimension: 3\nsizes: " + sizes + "\nspacing: 1 1 1\nencoding: raw\nendian: little\n\n";
}

/// Files of one bad-input corpus, sorted; the corpus's controls (valid files that must read) are left out.
std::vector<fs::path> corpus(const std::string& name) {
  static const std::set<std::string> controls = {
      "README.md",    "valid_triangle.glb", "tetra_19_units_cm.fbx", "tetra_19_units_m.fbx",
      "good_4x4.png", "good_grey_1bit.png", "good_palette_2bit.png"};
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(forensim::test::tests_dir() / "corpus" / name)) {
    if (entry.is_regular_file() && controls.count(entry.path().filename().string()) == 0) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// `words` followed by `tail`: a command line and the options that keep its run quick.
std::vector<std::string> followed_by(std::vector<std::string> words, const std::vector<std::string>& tail) {
  words.insert(words.end(), tail.begin(), tail.end());
  return words;
}

std::vector<fs::path> joined(std::initializer_list<std::vector<fs::path>> lists) {
  std::vector<fs::path> all;
  for (const auto& list : lists) all.insert(all.end(), list.begin(), list.end());
  return all;
}

/// The hostile files and output places of one test, made in its scratch folder.
class HostileFiles {
 public:
  explicit HostileFiles(const fs::path& root) : m_root(root) {
    fs::create_directories(m_root / "made");
    fs::create_directories(m_root / "out");
    write_bytes(m_root / "a_file", "a regular file, not a folder\n");
    fs::create_directories(m_root / "a_folder");
    fs::create_directories(m_root / "read_only");
    fs::permissions(m_root / "read_only", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    write_bytes(m_root / "cube.obj", cube_obj(40.0));
  }
  ~HostileFiles() {
    std::error_code ec;
    fs::permissions(m_root / "read_only", fs::perms::owner_all, fs::perm_options::add, ec);
  }
  HostileFiles(const HostileFiles&) = delete;
  HostileFiles& operator=(const HostileFiles&) = delete;

  /// A closed 40 mm cube, the good mesh beside a hostile option.
  fs::path cube() const { return m_root / "cube.obj"; }

  /// The four hostile paths every file option gets, with the option's extension: a path that does not exist,
  /// an empty file, a folder and 4 KiB of garbage.
  std::vector<fs::path> generic(const std::string& ext) {
    const fs::path missing = m_root / "made" / ("missing" + ext);
    const fs::path empty = made("empty" + ext, "");
    const fs::path folder = m_root / "made" / ("folder" + ext);
    fs::create_directories(folder);
    const fs::path garbage = made("garbage" + ext, garbage_bytes(4096, 29));
    return {missing, empty, folder, garbage};
  }

  /// Malformed meshes beyond the corpus: a GLB whose JSON chunk declares 2^31 bytes, OBJ vertex indices far
  /// past the end or before the start, a binary STL declaring 2^32 - 1 triangles.
  std::vector<fs::path> meshes() {
    std::vector<fs::path> files = generic(".obj");
    files.push_back(made("index_huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967296\n"));
    files.push_back(made("negative_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n"));
    std::string glb = forensim::read_file(forensim::test::tests_dir() / "corpus" / "mesh_io" / "valid_triangle.glb");
    if (glb.size() > 16) {
      glb[12] = 0, glb[13] = 0, glb[14] = 0, glb[15] = static_cast<char>(0x80);  // JSON chunk length 2^31
      files.push_back(made("json_length_2_31.glb", glb));
    }
    std::string stl(80, ' ');
    stl += std::string("\xff\xff\xff\xff", 4) + std::string(50, '\0');
    files.push_back(made("huge_count.stl", stl));
    files.push_back(made("garbage.glb", garbage_bytes(4096, 31)));
    files.push_back(made("garbage.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": 1e30}]}"));
    return files;
  }

  /// Malformed volumes beyond the corpus: a NRRD declaring 100000^3 voxels with none present, a header that
  /// names itself as its data file, a DICOM folder of garbage slices.
  std::vector<fs::path> volumes() {
    std::vector<fs::path> files = generic(".nrrd");
    files.push_back(made("sizes_100000_cubed.nrrd", nrrd_header("100000 100000 100000") + "xxxx"));
    files.push_back(made("self_data.nhdr",
                         "NRRD0004\ntype: short\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n"
                         "endian: little\ndata file: self_data.nhdr\n\n"));
    files.push_back(made("garbage.mha", garbage_bytes(4096, 37)));
    files.push_back(made("garbage.mhd",
                         "ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 100000\n"
                         "ElementType = MET_SHORT\nElementDataFile = LOCAL\n"));
    const fs::path dicom = m_root / "made" / "dicom_folder_of_garbage";
    fs::create_directories(dicom);
    for (int i = 0; i < 3; ++i) {
      write_bytes(dicom / ("slice" + std::to_string(i) + ".dcm"),
                  std::string(128, '\0') + "DICM" + garbage_bytes(512, 41 + i));
    }
    files.push_back(dicom);
    return files;
  }

  /// Well-formed files that no command can use (info and convert describe and convert them): a mesh whose
  /// vertices all lie at one point, a constant volume (no surface at any iso-value), a volume of one voxel.
  std::vector<fs::path> degenerate_meshes() {
    return {made("constant.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\nf 1 3 4\nf 2 4 3\nf 1 4 2\n")};
  }
  std::vector<fs::path> degenerate_volumes() {
    return {made("constant.nrrd", nrrd_header("16 16 16") + std::string(16 * 16 * 16 * 2, '\0')),
            made("one_voxel.nrrd", nrrd_header("1 1 1") + std::string(2, '\0'))};
  }

  /// Malformed pictures beyond the corpus.
  std::vector<fs::path> images() {
    std::vector<fs::path> files = generic(".png");
    files.push_back(made("garbage.jpg", garbage_bytes(4096, 43)));
    files.push_back(made("jpeg_header_only.jpg", std::string("\xff\xd8\xff\xe0", 4)));
    return files;
  }

  /// Malformed JSON: the job files, stroke files and guides' hostile set.
  std::vector<fs::path> json_files() {
    std::vector<fs::path> files = generic(".json");
    files.push_back(made("truncated.json", "{\"seed\": 1,"));
    files.push_back(made("nested_100000.json", std::string(100000, '[') + std::string(100000, ']')));
    files.push_back(made("root_is_array.json", "[1, 2, 3]"));
    files.push_back(made("root_is_string.json", "\"a job\""));
    files.push_back(made("unknown_key.json", "{\"no_such_key\": true}"));
    files.push_back(made("number_overflow.json", "{\"seed\": 1e999}"));
    files.push_back(made("nul_bytes.json", std::string("{\"seed\"\0\0\0: 1}", 14)));
    files.push_back(made("bad_utf8.json", "{\"\xff\xfe\": 1}"));
    return files;
  }

  /// Malformed CSV tables.
  std::vector<fs::path> csv_files() {
    std::vector<fs::path> files = generic(".csv");
    files.push_back(made("header_only.csv", "label,x,y,z\n"));
    files.push_back(made("nan.csv", "label,x,y,z\ng,nan,nan,nan\nn,inf,-inf,1e999\n"));
    files.push_back(made("unterminated_quote.csv", "label,x,y,z\n\"g,1,2,3\n"));
    files.push_back(made("long_line.csv", std::string(1 << 20, ',') + "\n"));
    files.push_back(made("words.csv", "a,b,c\nd,e,f\n"));
    return files;
  }

  /// Malformed CBOR template files: text, a byte string declaring 2^64 - 16 bytes, arrays nested 100000 deep.
  std::vector<fs::path> cbor_files() {
    std::vector<fs::path> files = generic(".cbor");
    files.push_back(made("json_text.cbor", "{\"skin\": 1}"));
    files.push_back(made("huge_length.cbor", std::string("\x5b\xff\xff\xff\xff\xff\xff\xff\xf0", 9)));
    files.push_back(made("huge_map.cbor", std::string("\xbb\x00\xff\xff\xff\xff\xff\xff\xff", 9)));
    files.push_back(made("nested_100000.cbor", std::string(100000, '\x81') + std::string(1, '\x00')));
    files.push_back(made("empty_map.cbor", std::string(1, '\xa0')));
    return files;
  }

  /// A fresh output path under the empty output folder (must not exist after a failed run).
  fs::path out(const std::string& name) const { return m_root / "out" / name; }

  /// Output paths that cannot be written: below a regular file, an existing folder for a file output or an
  /// existing file for a folder output, and in a read-only folder unless running as root. (A missing parent
  /// folder is no error: forensim creates the parents of its outputs.)
  std::vector<fs::path> bad_outputs(const std::string& name, bool file_output) const {
    std::vector<fs::path> paths = {m_root / "a_file" / name, file_output ? m_root / "a_folder" : m_root / "a_file"};
    if (geteuid() != 0) paths.push_back(m_root / "read_only" / name);
    return paths;
  }

 private:
  fs::path made(const std::string& name, const std::string& bytes) {
    const fs::path p = m_root / "made" / name;
    write_bytes(p, bytes);
    return p;
  }

  fs::path m_root;
};

/// `arguments` with the hostile path put where "{}" stands; the message must name the file.
HostileCase with_input(std::vector<std::string> arguments, const fs::path& input, const fs::path& output) {
  for (auto& a : arguments) {
    if (a == "{}") a = input.string();
  }
  // A TetGen mesh is a .node and .ele pair: either may be the one named.
  const bool tetgen = input.extension() == ".node" || input.extension() == ".ele";
  return {std::move(arguments), (tetgen ? input.stem() : input.filename()).string(), output};
}

void add_inputs(std::vector<HostileCase>& cases, const std::vector<std::string>& arguments,
                const std::vector<fs::path>& inputs, const fs::path& output) {
  for (const auto& input : inputs) cases.push_back(with_input(arguments, input, output));
}

/// The output `name` in each unwritable place; `arguments` hold "{}" where the output path goes.
void add_bad_outputs(std::vector<HostileCase>& cases, const HostileFiles& files,
                     const std::vector<std::string>& arguments, const std::string& name, bool file_output) {
  for (const auto& output : files.bad_outputs(name, file_output)) {
    HostileCase c = with_input(arguments, output, output);
    // The message names the place it could not write: the output, or the folder it could not be made in.
    c.names = (fs::exists(output) ? output : output.parent_path()).filename().string();
    cases.push_back(std::move(c));
  }
}

struct HostileFixture : ::testing::Test {
  fs::path root = forensim::test::scratch_dir("hostile");
  HostileFiles files{root};
};

}  // namespace

TEST_F(HostileFixture, HostileInfo) {
  std::vector<HostileCase> cases;
  add_inputs(cases, {"info", "{}"},
             joined({corpus("mesh_io"), corpus("volume"), corpus("image"), corpus("tet_io"), files.meshes(),
                     files.volumes(), files.generic(".msh"), files.generic(".vtu"), files.generic(".node")}),
             {});
  add_inputs(cases, {"info", "--json", "{}"}, joined({corpus("mesh_io"), files.volumes()}), {});
  run_hostile("info", cases);
}

TEST_F(HostileFixture, HostileConvert) {
  std::vector<HostileCase> cases;
  const auto obj = files.out("converted.obj");
  const auto msh = files.out("converted.msh");
  add_inputs(cases, {"convert", "{}", obj.string()},
             joined({corpus("mesh_io"), corpus("image"), corpus("volume"), files.meshes()}), obj);
  add_inputs(cases, {"convert", "--repair", "{}", obj.string()},
             joined({corpus("mesh_io"), files.meshes(), files.degenerate_meshes()}), obj);
  add_inputs(cases, {"convert", "{}", msh.string()}, joined({corpus("tet_io"), files.generic(".msh")}), msh);
  add_bad_outputs(cases, files, {"convert", files.cube().string(), "{}"}, "converted.obj", true);
  run_hostile("convert", cases);
}

TEST_F(HostileFixture, HostileIsosurface) {
  std::vector<HostileCase> cases;
  const auto obj = files.out("surface.obj");
  add_inputs(
      cases, {"isosurface", "{}", "--iso", "500", "-o", obj.string()},
      joined({corpus("volume"), files.volumes(), files.degenerate_volumes(), corpus("mesh_io"), corpus("image")}), obj);
  add_bad_outputs(cases, files, {"isosurface", "--phantom-voxel", "8", "--iso", "500", "-o", "{}"}, "surface.obj",
                  true);
  run_hostile("isosurface", cases);
}

TEST_F(HostileFixture, HostileTetrahedralize) {
  std::vector<HostileCase> cases;
  const auto msh = files.out("tets.msh");
  const std::string cube = files.cube().string();
  add_inputs(cases, {"tetrahedralize", "--skin", "{}", "--nodes", "200", "-o", msh.string()},
             joined({corpus("mesh_io"), corpus("volume"), corpus("image"), files.meshes(), files.degenerate_meshes()}),
             msh);
  add_inputs(cases, {"tetrahedralize", "--skin", cube, "--bone", "{}", "--nodes", "200", "-o", msh.string()},
             joined({corpus("mesh_io"), files.meshes(), files.degenerate_meshes()}), msh);
  add_inputs(cases, {"tetrahedralize", "--ct", "{}", "--nodes", "200", "-o", msh.string()},
             joined({corpus("volume"), files.volumes(), files.degenerate_volumes(), corpus("mesh_io")}), msh);
  add_bad_outputs(cases, files, {"tetrahedralize", "--skin", cube, "--nodes", "200", "-o", "{}"}, "tets.msh", true);
  add_bad_outputs(cases, files, {"tetrahedralize", "--skin", cube, "--nodes", "200", "--model", "{}"}, "model", false);
  run_hostile("tetrahedralize", cases);
}

TEST_F(HostileFixture, HostilePhantom) {
  std::vector<HostileCase> cases;
  add_bad_outputs(cases, files, {"phantom", "arm", "--voxel", "8", "-o", "{}"}, "arm", false);
  add_bad_outputs(cases, files, {"phantom", "forearm-uv", "--resolution", "64", "--picture-size", "64", "-o", "{}"},
                  "forearm", false);
  run_hostile("phantom", cases);
}

TEST_F(HostileFixture, HostileRender) {
  std::vector<HostileCase> cases;
  const auto png = files.out("picture.png");
  const std::string cube = files.cube().string();
  const std::vector<std::string> small = {"--size", "16", "--samples", "1", "-o", png.string()};
  const auto args = [&](std::vector<std::string> a) { return followed_by(std::move(a), small); };
  add_inputs(cases, args({"render", "{}"}),
             joined({corpus("mesh_io"), corpus("volume"), corpus("image"), files.meshes()}), png);
  add_inputs(cases, args({"render", cube, "{}"}), joined({corpus("mesh_io"), files.meshes()}), png);
  add_bad_outputs(cases, files, {"render", cube, "--size", "16", "--samples", "1", "-o", "{}"}, "picture.png", true);
  run_hostile("render", cases);
}

TEST_F(HostileFixture, HostileMummify) {
  std::vector<HostileCase> cases;
  const auto out = files.out("mummify");
  const std::vector<std::string> quick = {"--size", "small", "--days", "0.01", "--frames", "1", "--no-pictures"};
  add_inputs(cases, {"mummify", "{}", "-o", out.string()},
             joined({files.json_files(), corpus("mesh_io"), corpus("volume")}), out);
  // Body model folders: missing, empty, a file, and copies of a good model (a tetrahedralized cube) with each
  // of its files replaced by garbage, cut in half, removed, or swapped with the other mesh.
  std::vector<fs::path> models = files.generic("");
  const fs::path good = root / "good_model";
  const auto made_model = run_cli_timed(
      {"tetrahedralize", "--skin", files.cube().string(), "--nodes", "200", "--model", good.string()}, k_time_limit_s);
  ASSERT_EQ(made_model.exit_code, 0) << made_model.output;
  for (const char* name : {"model.json", "volume.vtu", "skin.vtu"}) {
    ASSERT_TRUE(fs::exists(good / name)) << name;
    for (const char* change : {"garbage", "half", "removed", "swapped"}) {
      if (std::string(change) == "swapped" && std::string(name) == "model.json") continue;
      const fs::path folder = root / "made" / (std::string("model_") + change + "_" + name);
      fs::copy(good, folder, fs::copy_options::recursive);
      const std::string bytes = forensim::read_file(good / name);
      if (std::string(change) == "garbage") write_bytes(folder / name, garbage_bytes(4096, 47));
      if (std::string(change) == "half") write_bytes(folder / name, bytes.substr(0, bytes.size() / 2));
      if (std::string(change) == "removed") fs::remove(folder / name);
      if (std::string(change) == "swapped") {
        const std::string other = std::string(name) == "skin.vtu" ? "volume.vtu" : "skin.vtu";
        write_bytes(folder / name, forensim::read_file(good / other));
      }
      models.push_back(folder);
    }
  }
  auto model_args = std::vector<std::string>{"mummify", "--model", "{}", "-o", out.string()};
  model_args.insert(model_args.end(), quick.begin() + 2, quick.end());
  add_inputs(cases, model_args, models, out);
  auto phantom = std::vector<std::string>{"mummify", "--phantom", "arm"};
  phantom.insert(phantom.end(), quick.begin(), quick.end());
  phantom.insert(phantom.end(), {"-o", "{}"});
  add_bad_outputs(cases, files, phantom, "mummify", false);
  run_hostile("mummify", cases);
}

// --resume reads the output folder's checkpoint, curves and series back: each is replaced in turn by garbage,
// or removed, in a copy of a short good run. The runs read the small arm as a body model folder built once
// (reading it takes 0.1 s, building it 9 s).
TEST_F(HostileFixture, HostileMummifyResume) {
  const fs::path model = root / "arm_model";
  const auto built = run_cli_timed({"tetrahedralize", "--phantom", "arm", "--size", "small", "--model", model.string()},
                                   k_time_limit_s);
  ASSERT_EQ(built.exit_code, 0) << built.output;
  const fs::path good = root / "good_run";
  const std::vector<std::string> quick = {"mummify", "--model",       model.string(), "--frames",
                                          "1",       "--no-pictures", "--step-hours", "1"};
  auto args = [&](const std::string& days, const fs::path& out, bool resume) {
    std::vector<std::string> a = quick;
    a.insert(a.end(), {"--days", days, "-o", out.string()});
    if (resume) a.push_back("--resume");
    return a;
  };
  const auto first = run_cli_timed(args("0.125", good, false), k_time_limit_s);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::vector<HostileCase> cases;
  int k = 0;
  for (const std::string name : {"checkpoint.bin", "curves.csv", "desiccation.pvd", "skin.pvd"}) {
    ASSERT_TRUE(fs::exists(good / name)) << name;
    for (const bool remove : {false, true}) {
      // Without a checkpoint the run starts again; without skin.pvd (runs older than the skin series) it
      // starts a new series.
      if (remove && (name == "checkpoint.bin" || name == "skin.pvd")) continue;
      const fs::path copy = root / ("resume_" + std::to_string(k++));
      fs::copy(good, copy, fs::copy_options::recursive);
      if (remove) {
        fs::remove(copy / name);
      } else {
        write_bytes(copy / name, garbage_bytes(256, 53));
      }
      cases.push_back({args("0.25", copy, true), name, {}});
    }
  }
  run_hostile("mummify --resume", cases);
}

TEST_F(HostileFixture, HostileWound) {
  std::vector<HostileCase> cases;
  const auto out = files.out("wound");
  const std::vector<std::string> quick = {"--resolution", "32", "--picture-size", "0", "--times",
                                          "1h",           "-o", out.string()};
  const auto args = [&](std::vector<std::string> a) { return followed_by(std::move(a), quick); };
  add_inputs(cases, args({"wound", "--mesh", "{}"}),
             joined({corpus("mesh_io"), corpus("image"), corpus("volume"), files.meshes(), files.degenerate_meshes()}),
             out);
  add_inputs(cases, args({"wound", "--builtin", "cylinder", "--strokes", "{}"}),
             joined({files.json_files(), corpus("mesh_io")}), out);
  for (const char* option : {"--upper-skin", "--lower-skin"}) {
    add_inputs(cases, args({"wound", "--builtin", "cylinder", option, "{}"}),
               joined({corpus("image"), files.images(), corpus("mesh_io")}), out);
  }
  add_bad_outputs(
      cases, files,
      {"wound", "--builtin", "cylinder", "--resolution", "32", "--picture-size", "0", "--times", "1h", "-o", "{}"},
      "wound", false);
  run_hostile("wound", cases);
}

TEST_F(HostileFixture, HostileReconstruct) {
  std::vector<HostileCase> cases;
  const auto out = files.out("face");
  const std::vector<std::string> quick = {
      "--template-detail", "coarse", "--picture-size", "0", "--texture-size", "0", "--expressions", "none", "-o",
      out.string()};
  const auto args = [&](std::vector<std::string> a) { return followed_by(std::move(a), quick); };
  add_inputs(cases, args({"reconstruct", "--skull", "{}"}),
             joined({corpus("mesh_io"), corpus("volume"), corpus("image"), files.meshes(), files.volumes(),
                     files.degenerate_meshes(), files.degenerate_volumes()}),
             out);
  add_inputs(cases, args({"reconstruct", "--ct", "{}"}),
             joined({corpus("volume"), files.volumes(), files.degenerate_volumes(), corpus("mesh_io"), files.meshes()}),
             out);
  add_inputs(cases, args({"reconstruct", "--job", "{}"}), joined({files.json_files(), corpus("mesh_io")}), out);
  add_inputs(cases, args({"reconstruct", "--guides", "{}"}), files.json_files(), out);
  add_inputs(cases, args({"reconstruct", "--table", "{}"}), files.csv_files(), out);
  add_inputs(cases, args({"reconstruct", "--landmarks", "{}"}), joined({files.csv_files(), files.json_files()}), out);
  add_inputs(cases, args({"reconstruct", "--template", "{}"}), joined({files.cbor_files(), corpus("mesh_io")}), out);
  auto builtin = std::vector<std::string>{"reconstruct"};
  builtin.insert(builtin.end(), quick.begin(), quick.end() - 1);
  builtin.push_back("{}");
  add_bad_outputs(cases, files, builtin, "face", false);
  run_hostile("reconstruct", cases);
}

TEST_F(HostileFixture, HostileTemplateBuild) {
  std::vector<HostileCase> cases;
  const auto out = files.out("template");
  const std::vector<std::string> quick = {"--detail", "coarse", "--picture-size", "0", "--texture-size",
                                          "16",       "-o",     out.string()};
  const auto args = [&](std::vector<std::string> a) { return followed_by(std::move(a), quick); };
  const std::string cube = files.cube().string();
  add_inputs(cases, args({"template", "build", "--ct", "{}"}),
             joined({corpus("volume"), files.volumes(), files.degenerate_volumes(), corpus("mesh_io")}), out);
  add_inputs(cases, args({"template", "build", "--head", "{}", "--skin-landmarks", "auto"}),
             joined({corpus("mesh_io"), files.meshes(), files.degenerate_meshes(), corpus("image")}), out);
  add_inputs(cases, args({"template", "build", "--head", cube, "--skin-landmarks", "{}"}),
             joined({files.csv_files(), files.json_files()}), out);
  add_inputs(cases, args({"template", "build", "--head", cube, "--skin-landmarks", "auto", "--texture", "{}"}),
             joined({corpus("image"), files.images()}), out);
  add_bad_outputs(cases, files,
                  {"template", "build", "--builtin", "--detail", "coarse", "--picture-size", "0", "-o", "{}"},
                  "template", false);
  run_hostile("template build", cases);
}

TEST_F(HostileFixture, HostileServeAndBench) {
  std::vector<HostileCase> cases;
  const fs::path missing = root / "made" / "no_such_folder";
  cases.push_back({{"serve", missing.string(), "--port", "0"}, "no_such_folder", {}});
  cases.push_back({{"serve", files.cube().string(), "--port", "0"}, "cube.obj", {}});
  cases.push_back({{"serve", root.string(), "--web", missing.string(), "--port", "0"}, "no_such_folder", {}});
  cases.push_back({{"serve", root.string(), "--web", files.cube().string(), "--port", "0"}, "cube.obj", {}});
  cases.push_back({{"serve", root.string(), "--host", "256.0.0.1", "--port", "0"}, "256.0.0.1", {}});
  cases.push_back({{"bench", "no-such-system"}, "no-such-system", {}});
  cases.push_back({{"bench", "wound", "--size", "no-such-size"}, "no-such-size", {}});
  run_hostile("serve and bench", cases);
}
