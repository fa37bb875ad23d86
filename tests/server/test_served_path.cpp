// Paths a request names resolve only inside the served folder: "..", absolute paths, NUL bytes and links
// that lead out are refused; links that stay inside are followed.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "server/served_path.hpp"
#include "support/test_support.hpp"

using namespace forensim;
namespace fs = std::filesystem;

namespace {
struct Tree {
  fs::path base, root, outside;
  Tree() {
    base = test::scratch_dir("served_path");
    root = base / "served";
    outside = base / "secret";
    fs::create_directories(root / "run" / "maps");
    fs::create_directories(outside);
    std::ofstream(root / "run" / "maps" / "a.png") << "png";
    std::ofstream(outside / "key.txt") << "secret";
    fs::create_symlink(outside, root / "link_out");
    fs::create_symlink(outside / "key.txt", root / "run" / "file_link_out");
    fs::create_symlink(root / "run" / "maps", root / "link_in");
  }
};
}  // namespace

TEST(ServedPath, ResolvesFilesAndTheRootInside) {
  const Tree t;
  const ServedPath a = resolve_served_path(t.root, "run/maps/a.png");
  ASSERT_EQ(a.problem, ServedPathProblem::none) << a.message;
  EXPECT_EQ(a.path, fs::canonical(t.root / "run" / "maps" / "a.png"));
  EXPECT_EQ(resolve_served_path(t.root, "").path, fs::canonical(t.root));
  EXPECT_EQ(resolve_served_path(t.root, "./run/").path, fs::canonical(t.root / "run"));
  EXPECT_EQ(served_relative(t.root, a.path), "run/maps/a.png");
  EXPECT_EQ(served_relative(t.root, t.root), "");
}

TEST(ServedPath, RefusesTraversalAbsoluteAndOddBytes) {
  const Tree t;
  for (const std::string& bad :
       std::vector<std::string>{"../secret/key.txt", "run/../../secret/key.txt", "run/..", "..", "/etc/passwd",
                                "//etc/passwd", "run\\..\\..\\secret", std::string("run/a\0b", 7)}) {
    const ServedPath p = resolve_served_path(t.root, bad);
    EXPECT_EQ(p.problem, ServedPathProblem::malformed) << bad;
    EXPECT_TRUE(p.path.empty()) << bad;
    EXPECT_FALSE(p.message.empty());
  }
  EXPECT_EQ(resolve_served_path(t.root, std::string(5000, 'a')).problem, ServedPathProblem::malformed);
}

TEST(ServedPath, LinksOutAreRefusedLinksInsideFollowed) {
  const Tree t;
  EXPECT_EQ(resolve_served_path(t.root, "link_out/key.txt").problem, ServedPathProblem::outside);
  EXPECT_EQ(resolve_served_path(t.root, "link_out").problem, ServedPathProblem::outside);
  EXPECT_EQ(resolve_served_path(t.root, "run/file_link_out").problem, ServedPathProblem::outside);
  // A folder that does not exist yet under a link out is still outside (output folders go through this).
  EXPECT_EQ(resolve_served_path(t.root, "link_out/new_run", false).problem, ServedPathProblem::outside);
  const ServedPath in = resolve_served_path(t.root, "link_in/a.png");
  ASSERT_EQ(in.problem, ServedPathProblem::none) << in.message;
  EXPECT_EQ(in.path, fs::canonical(t.root / "run" / "maps" / "a.png"));
}

TEST(ServedPath, MissingAndNotYetCreated) {
  const Tree t;
  EXPECT_EQ(resolve_served_path(t.root, "run/none.png").problem, ServedPathProblem::missing);
  const ServedPath fresh = resolve_served_path(t.root, "new_run", false);
  ASSERT_EQ(fresh.problem, ServedPathProblem::none);
  EXPECT_EQ(fresh.path, fs::canonical(t.root) / "new_run");
  EXPECT_EQ(resolve_served_path(t.base / "nowhere", "x").problem, ServedPathProblem::missing);
}
