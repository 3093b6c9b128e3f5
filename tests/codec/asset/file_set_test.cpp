// File sets: names that could leave the set are refused, references
// resolve inside it, reads are bounded in bytes, and a folder's symbolic
// links may not point out of it.
#include "meshwave/file_set.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace meshwave {
namespace {

using ::testing::HasSubstr;

TEST(FileSetTest, RefusesNamesThatCouldLeaveTheSet) {
  EXPECT_TRUE(CheckFileSetName("a.gltf").ok());
  EXPECT_TRUE(CheckFileSetName("textures/wood grain.png").ok());
  EXPECT_TRUE(CheckFileSetName("..hidden/x").ok());  // a name, not ".."
  for (const char* bad : {"", "/etc/passwd", "C:/x.png", "c:x", "a\\b.png",
                          "../x", "a/../../x", "a/./b", "a//b", "a/", "x\n"}) {
    const Status s = CheckFileSetName(bad);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << bad;
  }
  EXPECT_THAT(CheckFileSetName("a\\b").message(),
              HasSubstr("contains a backslash"));
  EXPECT_THAT(CheckFileSetName("/x").message(), HasSubstr("is absolute"));
  EXPECT_THAT(CheckFileSetName("a/../b").message(),
              HasSubstr("has a \".\" or \"..\" segment"));
}

TEST(FileSetTest, ResolvesReferencesInsideTheSetOnly) {
  EXPECT_EQ(*ResolveFileSetReference("m.gltf", "m.bin"), "m.bin");
  EXPECT_EQ(*ResolveFileSetReference("models/m.gltf", "../tex/./b.png"),
            "tex/b.png");
  EXPECT_EQ(*ResolveFileSetReference("a/b/m.obj", "c//d.mtl"), "a/b/c/d.mtl");
  const auto escape = ResolveFileSetReference("models/m.gltf", "../../x.png");
  EXPECT_EQ(escape.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(
      escape.status().message(),
      HasSubstr("\"models/m.gltf\" refers to \"../../x.png\", which leaves "
                "the folder of the upload"));
  EXPECT_THAT(ResolveFileSetReference("m.gltf", "/x").status().message(),
              HasSubstr("is an absolute path"));
  EXPECT_THAT(
      ResolveFileSetReference("m.gltf", "https://x/y.bin").status().message(),
      HasSubstr("is a URI with a scheme"));
  EXPECT_THAT(ResolveFileSetReference("m.gltf", "a\\b").status().message(),
              HasSubstr("contains a backslash"));
  EXPECT_FALSE(ResolveFileSetReference("m.gltf", "").ok());
  EXPECT_FALSE(ResolveFileSetReference("m.gltf", "a/..").ok());
}

TEST(FileSetTest, MemorySetIsBoundedInBytes) {
  MemoryFileSet files(10);
  EXPECT_TRUE(files.Add("a", "12345").ok());
  EXPECT_EQ(files.Add("a", "x").code(), StatusCode::kInvalidArgument);
  const Status over = files.Add("b", "123456");
  EXPECT_EQ(over.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(over.message(), HasSubstr("past 10 bytes"));
  EXPECT_TRUE(files.Add("b", "12345").ok());
  EXPECT_EQ(*files.Read("a"), "12345");
  EXPECT_TRUE(files.Contains("b"));
  EXPECT_FALSE(files.Contains("c"));
  EXPECT_EQ(files.Read("c").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(files.Add("../c", "").code(), StatusCode::kInvalidArgument);
}

class DirectoryFileSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("meshwave_file_set_" + std::to_string(::getpid()));
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_ / "set/sub");
    Write(root_ / "set/a.bin", "0123456789");
    Write(root_ / "set/sub/b.png", "png");
    Write(root_ / "secret.txt", "secret");
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  static void Write(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
  }

  std::filesystem::path root_;
};

TEST_F(DirectoryFileSetTest, ReadsFilesOfTheFolderWithinItsBudget) {
  DirectoryFileSet files(root_ / "set", 12);
  EXPECT_EQ(*files.Read("a.bin"), "0123456789");
  EXPECT_EQ(*files.Read("a.bin"), "0123456789");  // once in the budget
  EXPECT_TRUE(files.Contains("sub/b.png"));
  const auto over = files.Read("sub/b.png");
  EXPECT_EQ(over.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(over.status().message(), HasSubstr("past 12 bytes"));
  EXPECT_EQ(files.Read("missing.png").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(files.Read("../secret.txt").status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(files.Read("sub").status().code(),
            StatusCode::kNotFound);  // a folder
}

TEST_F(DirectoryFileSetTest, RefusesSymbolicLinksOutOfTheFolder) {
  std::filesystem::create_symlink(root_ / "secret.txt", root_ / "set/link.png");
  std::filesystem::create_directory_symlink(root_, root_ / "set/up");
  std::filesystem::create_symlink("a.bin", root_ / "set/inside.bin");
  DirectoryFileSet files(root_ / "set");
  const auto link = files.Read("link.png");
  EXPECT_EQ(link.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(link.status().message(), HasSubstr("leads outside"));
  EXPECT_EQ(files.Read("up/secret.txt").status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_FALSE(files.Contains("link.png"));
  EXPECT_EQ(*files.Read("inside.bin"), "0123456789");
}

}  // namespace
}  // namespace meshwave
