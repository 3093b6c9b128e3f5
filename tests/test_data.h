// Paths to test data: the shared development meshes, the project's own
// sample meshes and the test corpus. One helper so every test finds them
// alike. The paths come from CMake and live in test_data.cpp alone, so that
// pointing MESHWAVE_SHARED_MESHES elsewhere rebuilds one file, and so that
// no other test object names a path of this clone (the compiler cache
// shares them between clones in other folders: tools/compiler_cache.sh).
//
// The shared meshes (../shared/data/meshes beside the repository) are not
// part of it: a test that needs them starts with
// MESHWAVE_REQUIRE_SHARED_MESH("name.ply") (or with no argument: the
// directory), which skips the test with one line saying what is missing, or
// fails it when the build was configured with
// -DMESHWAVE_REQUIRE_SHARED_MESHES=ON (CI: nothing is skipped silently).
// A test that needs only *a* mesh uses SampleMesh or a generated one.
#ifndef MESHWAVE_TESTS_TEST_DATA_H_
#define MESHWAVE_TESTS_TEST_DATA_H_

#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

namespace meshwave::testing {

// Whether this build runs under ASan or TSan (10-20 times slower): the
// suites on real meshes then check the same code paths on smaller
// refinements (the sanitizer stages of tools/sanitize.sh).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderSanitizer = true;  // GCC
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kUnderSanitizer = true;  // clang
#else
inline constexpr bool kUnderSanitizer = false;
#endif
#else
inline constexpr bool kUnderSanitizer = false;
#endif

std::filesystem::path SharedMeshDir();
// Whether a missing shared mesh fails a test rather than skips it.
bool SharedMeshesRequired();
std::filesystem::path SampleDataDir();
std::filesystem::path TestDataDir();
std::filesystem::path CliPath();
// The programs and directories of this build that the end-to-end tests use.
std::filesystem::path ServerPath();           // meshwave-server
std::filesystem::path DieWithChildrenPath();  // tests/process's helper
std::filesystem::path SourceDir();            // the repository
std::filesystem::path BuildDir();             // this build tree
std::filesystem::path CMakeCommand();         // the cmake that configured it

inline std::filesystem::path SharedMesh(const std::string& name) {
  return SharedMeshDir() / name;
}
inline std::filesystem::path SampleMesh(const std::string& name) {
  return SampleDataDir() / name;
}
inline std::filesystem::path TestData(const std::string& name) {
  return TestDataDir() / name;
}

// The shared textured and coloured meshes (../shared/data/textured, beside
// the shared meshes: glTF, OBJ + MTL + PNG, coloured PLY, each in a folder
// with its sidecar files), e.g. SharedTextured("spot/cow.obj").
std::filesystem::path SharedTexturedDir();
inline std::filesystem::path SharedTextured(const std::string& name) {
  return SharedTexturedDir() / name;
}
// Empty when the shared textured files `names` are present; else the line
// that says what is missing and how to get it.
std::string SharedTexturedMissing(std::initializer_list<std::string> names);

// Every mesh file (.ply/.obj/.off) in the shared directory, sorted by name;
// empty when the directory is missing.
std::vector<std::filesystem::path> AllSharedMeshes();

// Empty when the shared meshes `names` (none: the directory with at least
// one mesh) are present; else the line that says what is missing and how
// to get it.
std::string SharedMeshesMissing(std::initializer_list<std::string> names);

}  // namespace meshwave::testing

// Skips (or, with MESHWAVE_REQUIRE_SHARED_MESHES=ON, fails) the current
// test, or every test of a suite from SetUpTestSuite, when a shared mesh is
// missing. Arguments: file names in the shared directory, or none.
#define MESHWAVE_REQUIRE_SHARED_MESH(...) \
  MESHWAVE_REQUIRE_SHARED_FILES_(::meshwave::testing::SharedMeshesMissing({__VA_ARGS__}))

// The same for the shared textured files (SharedTextured names).
#define MESHWAVE_REQUIRE_SHARED_TEXTURED(...) \
  MESHWAVE_REQUIRE_SHARED_FILES_(::meshwave::testing::SharedTexturedMissing({__VA_ARGS__}))

// `missing`: what is missing, empty when nothing is.
#define MESHWAVE_REQUIRE_SHARED_FILES_(missing)                           \
  do {                                                                    \
    const std::string mw_missing_ = (missing);                            \
    if (!mw_missing_.empty()) {                                           \
      if (::meshwave::testing::SharedMeshesRequired()) {                  \
        GTEST_FAIL() << mw_missing_                                       \
                     << " (required: MESHWAVE_REQUIRE_SHARED_MESHES=ON)"; \
      }                                                                   \
      GTEST_SKIP() << mw_missing_;                                        \
    }                                                                     \
  } while (false)

#endif  // MESHWAVE_TESTS_TEST_DATA_H_
