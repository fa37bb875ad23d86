// Large-mesh round trips through every writer/reader pair, printing sizes and times (no timing assertions).
// Run: build/<dir>/tests/forensim_slowtest_tet_io

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <functional>

#include "support/test_support.hpp"
#include "tet_io/gmsh_io.hpp"
#include "tet_io/sample_tet_mesh.hpp"
#include "tet_io/tetgen_io.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"

using namespace forensim;

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

TEST(TetIoLarge, RoundTripsOfAMillionTets) {
  const TetMesh mesh = test::sample_tet_mesh(60, 60, 50);  // 1,080,000 tets, 189,771 nodes
  const auto dir = test::scratch_dir("large");
  struct Format {
    const char* name;
    std::function<void(const std::filesystem::path&)> write;
    std::function<TetMesh(const std::filesystem::path&)> read;
    bool fields;
  };
  auto vtu = [&](VtuEncoding encoding, bool compress) {
    return [&mesh, encoding, compress](const std::filesystem::path& p) {
      VtuOptions o;
      o.encoding = encoding;
      o.compress = compress;
      write_vtu(p, mesh, o);
    };
  };
  const std::vector<Format> formats = {
      {"msh_ascii", [&](const auto& p) { write_gmsh(p, mesh); }, [](const auto& p) { return read_gmsh(p); }, false},
      {"msh_binary", [&](const auto& p) { write_gmsh(p, mesh, true); }, [](const auto& p) { return read_gmsh(p); },
       false},
      {"tetgen", [&](const auto& p) { write_tetgen(p, mesh); }, [](const auto& p) { return read_tetgen(p); }, true},
      {"vtu_ascii", vtu(VtuEncoding::ascii, false), [](const auto& p) { return read_vtu(p); }, true},
      {"vtu_base64", vtu(VtuEncoding::inline_base64, false), [](const auto& p) { return read_vtu(p); }, true},
      {"vtu_appended", vtu(VtuEncoding::appended_raw, false), [](const auto& p) { return read_vtu(p); }, true},
      {"vtu_appended_zlib", vtu(VtuEncoding::appended_raw, true), [](const auto& p) { return read_vtu(p); }, true},
  };
  std::printf("%zu nodes, %zu tets, 2 vertex + 2 tet fields\n", mesh.vertex_count(), mesh.tet_count());
  for (const Format& f : formats) {
    const auto path = dir / f.name;
    auto start = std::chrono::steady_clock::now();
    f.write(path);
    const double write_s = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const TetMesh back = f.read(path);
    const double read_s = seconds_since(start);
    const auto size = std::filesystem::exists(path) ? std::filesystem::file_size(path)
                                                    : std::filesystem::file_size(path.string() + ".node") +
                                                          std::filesystem::file_size(path.string() + ".ele");
    std::printf("%-18s %8.1f MB  write %6.2f s  read %6.2f s\n", f.name, static_cast<double>(size) / 1e6, write_s,
                read_s);
    test::expect_same_geometry(mesh, back);
    if (f.fields) test::expect_same_fields(mesh.tet_fields, back.tet_fields);
  }
}
