// The originals' store: names, digests that depend on the files and their
// names alone, durable content-addressed blobs shared between originals,
// and damage found when a file is read back.
#include "original_store.h"

#include <gtest/gtest.h>

#include <fstream>

#include "e2e/cli_runner.h"
#include "sha256.h"

namespace meshwave::server {
namespace {

using meshwave::testing::CountFilesIn;
using meshwave::testing::TempDir;

TEST(OriginalStoreTest, ChecksFileNames) {
  for (std::string_view good : {"cow.obj", "textures/cow.png", "a b.mtl", ".hidden"}) {
    EXPECT_TRUE(CheckOriginalFileName(good).ok()) << good;
  }
  for (std::string_view bad : {"", "../cow.obj", "a/../b", "/etc/passwd", "a//b", "a/./b",
                               "a\\b", "dir/", "tab\there"}) {
    auto s = CheckOriginalFileName(bad);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << bad;
  }
  EXPECT_FALSE(CheckOriginalFileName(std::string(201, 'a')).ok());
}

TEST(OriginalStoreTest, DigestDependsOnFilesAndNamesNotOnTheirOrder) {
  const std::vector<OriginalPart> a = {{"cow.obj", "v 0 0 0"}, {"cow.mtl", "newmtl m"}};
  const std::vector<OriginalPart> b = {{"cow.mtl", "newmtl m"}, {"cow.obj", "v 0 0 0"}};
  auto oa = DescribeOriginal(a, "cow.obj");
  auto ob = DescribeOriginal(b, "cow.obj");
  ASSERT_TRUE(oa.ok() && ob.ok());
  EXPECT_EQ(oa->digest, ob->digest);
  EXPECT_EQ(oa->format, "obj");
  EXPECT_EQ(oa->bytes, 15u);
  ASSERT_EQ(oa->files.size(), 2u);
  EXPECT_EQ(oa->files[0].name, "cow.mtl");  // by name
  EXPECT_EQ(oa->files[1].sha256, Sha256Hex("v 0 0 0"));
  EXPECT_EQ(oa->digest, Sha256Hex(ManifestText(*oa)));
  // Another name, another main file or other bytes: another original.
  EXPECT_NE(DescribeOriginal({{"cow2.obj", "v 0 0 0"}, {"cow.mtl", "newmtl m"}}, "cow2.obj")->digest,
            oa->digest);
  EXPECT_NE(DescribeOriginal(a, "cow.mtl")->digest, oa->digest);
  EXPECT_NE(DescribeOriginal({{"cow.obj", "v 0 0 1"}, {"cow.mtl", "newmtl m"}}, "cow.obj")->digest,
            oa->digest);
  // Refusals.
  EXPECT_EQ(DescribeOriginal(a, "cow.png").status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(DescribeOriginal({{"x.obj", "1"}, {"x.obj", "2"}}, "x.obj").ok());
  EXPECT_FALSE(DescribeOriginal({{"../x.obj", "1"}}, "../x.obj").ok());
  EXPECT_EQ(DescribeOriginal({{"Mesh.PLY", "ply"}}, "Mesh.PLY")->format, "ply");
}

TEST(OriginalStoreTest, WritesBlobsOnceAndReadsThemBack) {
  TempDir tmp;
  const std::vector<OriginalPart> first = {{"m.obj", "v 1 2 3"}, {"t.png", "PNG"}};
  const std::vector<OriginalPart> second = {{"n.obj", "v 4 5 6"}, {"t.png", "PNG"}};
  auto o1 = DescribeOriginal(first, "m.obj").value();
  auto o2 = DescribeOriginal(second, "n.obj").value();
  ASSERT_TRUE(WriteOriginal(tmp.path(), o1, first).ok());
  ASSERT_TRUE(WriteOriginal(tmp.path(), o2, second).ok());
  EXPECT_EQ(CountFilesIn(tmp.path() / "originals"), 3u);  // the texture once
  for (const OriginalFile& f : o1.files) {
    auto bytes = ReadOriginalFile(tmp.path(), f);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    EXPECT_EQ(Sha256Hex(*bytes), f.sha256);
  }
  // Damage and loss are named, never returned as content.
  const OriginalFile& obj = o1.files[0];
  std::ofstream(OriginalBlobPath(tmp.path(), obj.sha256), std::ios::binary) << "v 9 9 9";
  auto damaged = ReadOriginalFile(tmp.path(), obj);
  ASSERT_FALSE(damaged.ok());
  EXPECT_NE(damaged.status().message().find("damaged"), std::string::npos);
  std::filesystem::remove(OriginalBlobPath(tmp.path(), obj.sha256));
  auto missing = ReadOriginalFile(tmp.path(), obj);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("missing"), std::string::npos);
}

}  // namespace
}  // namespace meshwave::server
