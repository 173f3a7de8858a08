// Tests of common/atomic_file.hpp: the content arrives whole, replaces the old file, leaves no
// staging file, and failures are common::IoError naming the file.
#include "common/atomic_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("mpmxdem_atomic_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace

TEST(AtomicFile, WritesReplacesAndLeavesNoStagingFile) {
  const fs::path dir = scratch("write");
  const fs::path f = dir / "means.csv";
  std::string big(3'000'000, 'x');  // more than one write() may take
  big[12345] = '\0';                // binary content arrives as it is
  common::write_file_atomic(f, big);
  EXPECT_EQ(slurp(f), big);
  common::write_file_atomic(f, "short\n");
  EXPECT_EQ(slurp(f), "short\n");
  EXPECT_FALSE(fs::exists(common::staging_path(f)));
  EXPECT_EQ(common::staging_path(f), dir / "means.csv.tmp");
}

TEST(AtomicFile, PublishRenamesAStagedFile) {
  const fs::path dir = scratch("publish");
  const fs::path f = dir / "series.h5";
  std::ofstream(common::staging_path(f)) << "staged";
  std::ofstream(f) << "old";
  common::publish_file(common::staging_path(f), f);
  EXPECT_EQ(slurp(f), "staged");
  EXPECT_FALSE(fs::exists(common::staging_path(f)));
}

TEST(AtomicFile, FailuresAreIoErrorsNamingTheFile) {
  const fs::path dir = scratch("fail");
  const fs::path missing_dir = dir / "no" / "such" / "dir" / "job.toml";
  try {
    common::write_file_atomic(missing_dir, "x");
    ADD_FAILURE() << "writing into a missing directory succeeded";
  } catch (const common::IoError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("job.toml.tmp"), std::string::npos) << m;
    EXPECT_NE(m.find("No such file or directory"), std::string::npos) << m;
  }
  const fs::path f = dir / "checkpoint.h5";
  try {
    common::publish_file(common::staging_path(f), f);  // nothing staged
    ADD_FAILURE() << "publishing a missing staged file succeeded";
  } catch (const common::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.h5.tmp"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(f));
}

TEST(AtomicFile, ReadFileBytesReturnsTheBytesAsTheyAre) {
  const fs::path dir = scratch("read");
  std::string bytes = "line\r\n";
  bytes += '\0';
  bytes += "\xff tail";
  common::write_file_atomic(dir / "f.bin", bytes);
  EXPECT_EQ(common::read_file_bytes(dir / "f.bin"), bytes);
  EXPECT_EQ(common::read_file_bytes(dir / "none.bin"), "");
}
