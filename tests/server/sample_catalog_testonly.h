// A catalog of sample meshes for the tests that serve, stream or fetch
// them (not for the tests of ingest itself): ingested once per build by the
// real `meshwave-server ingest --fidelity 0` and copied into each test's
// own directory. ctest runs every test in its own process, so a suite's
// SetUpTestSuite ingests once per test; under the sanitizers that was 25 s
// a test. The copy is the test's to change (uploads, deletes, damage).
//
// The ingested original is kept in BUILD/test-catalogs/KEY, KEY naming the
// server binary (size, mtime) and the meshes (name, content): a rebuilt
// server or a changed sample ingests again. Concurrent tests (ctest -j)
// wait on an flock while the first ingests.
#ifndef MESHWAVE_TESTS_SERVER_SAMPLE_CATALOG_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_SAMPLE_CATALOG_TESTONLY_H_

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>
#include <vector>

#include "e2e/cli_runner.h"
#include "server/server_process_testonly.h"
#include "test_data.h"

namespace meshwave::testing {

namespace sample_catalog_internal {

// The server binary by size and mtime; a mesh by name and content (the
// tests that copy a sample under another name copy it anew each time).
inline std::string BinaryStamp(const std::filesystem::path& p) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(p, ec);
  const auto mtime =
      std::filesystem::last_write_time(p, ec).time_since_epoch().count();
  return p.string() + ":" + std::to_string(size) + ":" + std::to_string(mtime) +
         ";";
}
inline std::string MeshStamp(const std::filesystem::path& p) {
  return p.filename().string() + ":" +
         std::to_string(std::hash<std::string>{}(ReadBytes(p))) + ";";
}

// An exclusive flock held for the object's life.
class FileLock {
 public:
  explicit FileLock(const std::filesystem::path& path)
      : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_;
};

}  // namespace sample_catalog_internal

// Fills `catalog` (a directory that must not exist yet) with the catalog of
// `meshes` ingested at --fidelity 0 (one remesh at about each input's
// density: these tests are about serving, and tests/server/ingest_test.cpp
// and the fidelity tests cover the default), with `ingest_options` added to
// the command. Fails the test on an error.
inline void CopySampleCatalog(
    const std::filesystem::path& catalog,
    const std::vector<std::filesystem::path>& meshes,
    const std::vector<std::string>& ingest_options = {}) {
  namespace fs = std::filesystem;
  using namespace sample_catalog_internal;
  std::string stamp = BinaryStamp(ServerPath());
  for (const auto& o : ingest_options) stamp += o + ";";
  for (const auto& m : meshes) stamp += MeshStamp(m);
  char key[17];
  std::snprintf(key, sizeof key, "%016zx", std::hash<std::string>{}(stamp));
  const fs::path root = BuildDir() / "test-catalogs";
  fs::create_directories(root);
  const fs::path original = root / key;
  {
    FileLock lock(root / (std::string(key) + ".lock"));
    ASSERT_TRUE(lock.held()) << "cannot lock " << root;
    if (!fs::exists(original / "complete")) {
      fs::remove_all(original);  // a run killed while ingesting
      fs::create_directories(original);
      std::vector<std::string> args = {"ingest", "--catalog",
                                       (original / "catalog").string(),
                                       "--fidelity", "0"};
      args.insert(args.end(), ingest_options.begin(), ingest_options.end());
      for (const auto& m : meshes) args.push_back(m.string());
      const pid_t pid = SpawnServer(args, original / "ingest.log");
      ASSERT_EQ(WaitExit(pid, std::chrono::seconds(300)), 0)
          << ReadBytes(original / "ingest.log");
      std::ofstream(original / "complete") << stamp << "\n";
    }
  }
  std::error_code ec;
  fs::copy(original / "catalog", catalog, fs::copy_options::recursive, ec);
  ASSERT_FALSE(ec) << "copying " << original / "catalog"
                   << " to " << catalog << ": " << ec.message();
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_SAMPLE_CATALOG_TESTONLY_H_
