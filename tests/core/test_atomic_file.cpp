#include <gtest/gtest.h>

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
