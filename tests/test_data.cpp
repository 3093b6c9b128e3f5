#include "test_data.h"

#include <algorithm>

namespace meshwave::testing {

std::filesystem::path SharedMeshDir() { return MESHWAVE_SHARED_MESHES; }
bool SharedMeshesRequired() { return MESHWAVE_REQUIRE_SHARED_MESHES != 0; }
std::filesystem::path SampleDataDir() { return MESHWAVE_SAMPLE_DATA; }
std::filesystem::path TestDataDir() { return MESHWAVE_TEST_DATA; }
std::filesystem::path CliPath() { return MESHWAVE_CLI_PATH; }
std::filesystem::path ServerPath() { return MESHWAVE_SERVER_PATH; }
std::filesystem::path DieWithChildrenPath() { return MESHWAVE_DIE_WITH_CHILDREN; }
std::filesystem::path SourceDir() { return MESHWAVE_SOURCE_DIR; }
std::filesystem::path BuildDir() { return MESHWAVE_BUILD_DIR; }
std::filesystem::path CMakeCommand() { return MESHWAVE_CMAKE_COMMAND; }

std::vector<std::filesystem::path> AllSharedMeshes() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e :
       std::filesystem::directory_iterator(SharedMeshDir(), ec)) {
    const auto ext = e.path().extension().string();
    if (ext == ".ply" || ext == ".obj" || ext == ".off")
      out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string SharedMeshesMissing(std::initializer_list<std::string> names) {
  const std::string how =
      ": the shared development meshes are not part of the repository (put "
      "shared/ beside "
      "it, or configure with -DMESHWAVE_SHARED_MESHES=DIR)";
  if (names.size() == 0) {
    return AllSharedMeshes().empty()
               ? "no shared meshes in " + SharedMeshDir().string() + how
               : "";
  }
  std::string missing;
  for (const auto& name : names) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(SharedMesh(name), ec)) {
      missing += (missing.empty() ? "" : ", ") + name;
    }
  }
  return missing.empty() ? ""
                         : "shared mesh " + missing + " not found in " +
                               SharedMeshDir().string() + how;
}

std::filesystem::path SharedTexturedDir() {
  return SharedMeshDir().parent_path() / "textured";
}

std::string SharedTexturedMissing(std::initializer_list<std::string> names) {
  std::string missing;
  for (const auto& name : names) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(SharedTextured(name), ec)) {
      missing += (missing.empty() ? "" : ", ") + name;
    }
  }
  return missing.empty()
             ? ""
             : "shared textured file " + missing + " not found in " +
                   SharedTexturedDir().string() +
                   ": the shared development meshes are not part of the "
                   "repository (put shared/ beside it, or configure with "
                   "-DMESHWAVE_SHARED_MESHES=DIR: textured/ is read beside "
                   "that folder)";
}

}  // namespace meshwave::testing
