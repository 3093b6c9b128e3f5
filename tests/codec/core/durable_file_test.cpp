// WriteFileDurably, the one crash-safe file write (codec mesh writers,
// server store, client state, CLI): whole files, no temporaries left, and
// failures that leave the old file and name the cause.
#include "core/durable_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <string>

#include "e2e/cli_runner.h"

namespace meshwave {
namespace {

using meshwave::testing::CountFilesIn;
using meshwave::testing::ReadBytes;
using meshwave::testing::TempDir;


TEST(DurableFileTest, WritesAndReplacesWholeFilesWithoutTemporaries) {
  TempDir tmp;
  ASSERT_TRUE(WriteFileDurably(tmp / "f.bin", "hello").ok());
  EXPECT_EQ(ReadBytes(tmp / "f.bin"), "hello");
  ASSERT_TRUE(WriteFileDurably(tmp / "f.bin", "bye").ok());
  EXPECT_EQ(ReadBytes(tmp / "f.bin"), "bye");
  ASSERT_TRUE(WriteFileDurably(tmp / "empty", "").ok());
  EXPECT_EQ(std::filesystem::file_size(tmp / "empty"), 0u);
  EXPECT_EQ(CountFilesIn(tmp.path()), 2u);
}

TEST(DurableFileTest, RelativePathWritesIntoTheWorkingDirectory) {
  TempDir tmp;
  const auto before = std::filesystem::current_path();
  std::filesystem::current_path(tmp.path());
  const Status s = WriteFileDurably("rel.bin", "x");
  std::filesystem::current_path(before);
  ASSERT_TRUE(s.ok()) << s.ToString();
  EXPECT_EQ(ReadBytes(tmp / "rel.bin"), "x");
}

TEST(DurableFileTest, MissingOrUnusableDirectoryIsAnIoErrorNamingThePath) {
  TempDir tmp;
  const Status missing = WriteFileDurably(tmp / "missing/f.bin", "x");
  EXPECT_EQ(missing.code(), StatusCode::kIoError);
  EXPECT_NE(missing.message().find("missing"), std::string::npos) << missing.message();
  // A regular file where a directory should be (ENOTDIR also as root, who
  // would pass a permission check).
  ASSERT_TRUE(WriteFileDurably(tmp / "plain", "x").ok());
  const Status not_dir = WriteFileDurably(tmp / "plain/f.bin", "x");
  EXPECT_EQ(not_dir.code(), StatusCode::kIoError);
  EXPECT_NE(not_dir.message().find("Not a directory"), std::string::npos) << not_dir.message();
  EXPECT_EQ(CountFilesIn(tmp.path()), 1u);
}

TEST(DurableFileTest, FullDiskKeepsTheOldFileAndLeavesNoTemporary) {
  TempDir tmp;
  ASSERT_TRUE(WriteFileDurably(tmp / "f.bin", "old").ok());
  // A disk that fills up: writes past 64 KiB fail with EFBIG (SIGXFSZ
  // ignored), as the server's fault test does without mount rights.
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 64 << 10;
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const Status s = WriteFileDurably(tmp / "f.bin", std::string(1 << 20, 'x'));
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("cannot write"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find(std::string(kDurableTempPrefix)), std::string::npos);
  EXPECT_EQ(ReadBytes(tmp / "f.bin"), "old");
  EXPECT_EQ(CountFilesIn(tmp.path()), 1u);
}

TEST(DurableFileTest, SyncDirectoryRefusesAMissingDirectory) {
  TempDir tmp;
  EXPECT_TRUE(SyncDirectory(tmp.path()).ok());
  EXPECT_EQ(SyncDirectory(tmp / "missing").code(), StatusCode::kIoError);
}

}  // namespace
}  // namespace meshwave
