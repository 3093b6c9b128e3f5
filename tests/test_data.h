// Paths to test data: the shared development meshes, the project's own
// sample meshes and the test corpus. One helper so every test finds them alike.
#ifndef MESHWAVE_TESTS_TEST_DATA_H_
#define MESHWAVE_TESTS_TEST_DATA_H_

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace meshwave::testing {

inline std::filesystem::path SharedMesh(const std::string& name) {
  return std::filesystem::path(MESHWAVE_SHARED_MESHES) / name;
}
inline std::filesystem::path SampleMesh(const std::string& name) {
  return std::filesystem::path(MESHWAVE_SAMPLE_DATA) / name;
}
inline std::filesystem::path TestData(const std::string& name) {
  return std::filesystem::path(MESHWAVE_TEST_DATA) / name;
}
inline std::filesystem::path CliPath() { return MESHWAVE_CLI_PATH; }

// Every mesh file (.ply/.obj/.off) in the shared directory, sorted by name.
inline std::vector<std::filesystem::path> AllSharedMeshes() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e :
       std::filesystem::directory_iterator(MESHWAVE_SHARED_MESHES, ec)) {
    const auto ext = e.path().extension().string();
    if (ext == ".ply" || ext == ".obj" || ext == ".off") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_TEST_DATA_H_
