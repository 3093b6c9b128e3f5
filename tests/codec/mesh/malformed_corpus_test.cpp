// Every file in tests/data/malformed/ is refused with a ParseError that
// names the file and a line or an element; every file in
// tests/data/wellformed/ reads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "test_data.h"

namespace meshwave {
namespace {

std::vector<std::filesystem::path> FilesIn(const std::string& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(testing::TestData(dir))) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// True if `text` names a place: "line <n>", or a vertex, face or element.
// (Not std::regex: GCC 12 warns inside it under -O3 with sanitizers.)
bool NamesAPlace(const std::string& text) {
  for (const char* word : {"vertex", "face", "element"}) {
    if (text.find(word) != std::string::npos) return true;
  }
  for (size_t at = text.find("line "); at != std::string::npos;
       at = text.find("line ", at + 1)) {
    if (at + 5 < text.size() &&
        std::isdigit(static_cast<unsigned char>(text[at + 5]))) {
      return true;
    }
  }
  return false;
}

TEST(MeshCorpusTest, EveryFileIsRefusedNamingFileAndPlace) {
  const std::vector<std::filesystem::path> files = FilesIn("malformed");
  ASSERT_GE(files.size(), 40u);
  for (const std::filesystem::path& path : files) {
    SCOPED_TRACE(path.filename().string());
    Result<TriMesh> mesh = ReadMesh(path);
    ASSERT_FALSE(mesh.ok()) << "accepted";
    EXPECT_EQ(mesh.status().code(), StatusCode::kParseError)
        << mesh.status().ToString();
    const std::string& message = mesh.status().message();
    const std::string file = path.filename().string();
    const size_t at = message.find(file + ": ");
    ASSERT_NE(at, std::string::npos) << message;
    std::string after_name = message.substr(at + file.size());
    EXPECT_TRUE(NamesAPlace(after_name)) << message;
  }
}

TEST(MeshCorpusTest, EveryWellFormedFileReads) {
  for (const std::filesystem::path& path : FilesIn("wellformed")) {
    SCOPED_TRACE(path.filename().string());
    Result<TriMesh> mesh = ReadMesh(path);
    EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  }
}

}  // namespace
}  // namespace meshwave
