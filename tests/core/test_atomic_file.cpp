#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/run_folder.hpp"
#include "support/test_support.hpp"

using namespace forensim;

TEST(AtomicFile, UncommittedFileLeavesNothing) {
  const auto dir = test::scratch_dir("atomic");
  {
    AtomicFile f(dir / "out.txt");
    f.stream() << "partial";
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(AtomicFile, CommitMovesIntoPlaceAndRoundTrips) {
  const auto dir = test::scratch_dir("atomic");
  write_file_atomic(dir / "sub" / "a.bin", std::string("abc\0def", 7));
  EXPECT_EQ(read_file(dir / "sub" / "a.bin"), std::string("abc\0def", 7));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "sub"), {}), 1);
}

TEST(AtomicFile, ReadErrorsNameThePath) {
  const auto dir = test::scratch_dir("atomic");
  try {
    (void)read_file(dir / "missing.txt");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt"), std::string::npos);
  }
  EXPECT_THROW((void)read_file(dir), IoError);
  write_file_atomic(dir / "big", std::string(100, 'x'));
  EXPECT_THROW((void)read_file(dir / "big", 10), IoError);
}

TEST(OutputPath, GoodPathsPassAndCreateNothing) {
  const auto dir = test::scratch_dir("output_path");
  EXPECT_NO_THROW(check_output_path(dir / "new" / "deeper" / "out.glb", OutputKind::file));
  EXPECT_NO_THROW(check_output_path(dir / "new" / "folder", OutputKind::folder));
  EXPECT_NO_THROW(check_output_path(dir, OutputKind::folder));  // an existing folder is reused
  write_file_atomic(dir / "existing.txt", "x");
  EXPECT_NO_THROW(check_output_path(dir / "existing.txt", OutputKind::file));  // replaced atomically
  EXPECT_FALSE(std::filesystem::exists(dir / "new"));
}

TEST(OutputPath, BadPathsNameThePathAndTheProblem) {
  const auto dir = test::scratch_dir("output_path");
  write_file_atomic(dir / "a_file", "x");
  const auto message = [](const std::filesystem::path& path, OutputKind kind) -> std::string {
    try {
      check_output_path(path, kind);
    } catch (const IoError& e) {
      EXPECT_EQ(e.exit_code(), static_cast<int>(ErrorKind::io));
      return e.what();
    }
    return "";
  };
  const std::string below_a_file = message(dir / "a_file" / "sub" / "out.png", OutputKind::file);
  EXPECT_NE(below_a_file.find("a_file/sub/out.png"), std::string::npos) << below_a_file;
  EXPECT_NE(below_a_file.find("is not a folder"), std::string::npos) << below_a_file;
  EXPECT_NE(message(dir / "a_file", OutputKind::folder).find("a file of that name exists"), std::string::npos);
  EXPECT_NE(message(dir, OutputKind::file).find("is a folder"), std::string::npos);
  EXPECT_NE(message("", OutputKind::file).find("empty"), std::string::npos);
  if (::geteuid() != 0) {  // root may write anywhere
    std::filesystem::create_directories(dir / "read_only");
    std::filesystem::permissions(dir / "read_only",
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    const std::string read_only = message(dir / "read_only" / "new" / "out", OutputKind::folder);
    std::filesystem::permissions(dir / "read_only", std::filesystem::perms::owner_all);
    EXPECT_NE(read_only.find("not writable"), std::string::npos) << read_only;
  }
}

TEST(RunFolder, RecordsJobSeedTimingsAndOutputs) {
  const auto dir = test::scratch_dir("run");
  RunFolder run(dir, "test");
  run.set_seed(99);
  run.set_job({{"days", 3}});
  run.write("maps/a.txt", "hello");
  run.timings().add("stage", 1.5);
  run.write_record();
  const std::string record = read_file(dir / "run.json");
  const auto json = nlohmann::json::parse(record);
  EXPECT_EQ(json["seed"], 99);
  EXPECT_EQ(json["job"]["days"], 3);
  EXPECT_EQ(json["outputs"][0], "maps/a.txt");
  EXPECT_DOUBLE_EQ(json["timings_s"]["stage"].get<double>(), 1.5);
  EXPECT_EQ(json["forensim_version"], version_string());
}
