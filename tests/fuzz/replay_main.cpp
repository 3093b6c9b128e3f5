// A main() for the fuzz targets without libFuzzer: runs
// LLVMFuzzerTestOneInput on every file named on the command line or found
// (recursively) in the directories named, so that the seed and regression
// corpora run in every build, under the sanitizers of that build. Exit code
// 0 when every input ran; a finding aborts (the sanitizer or Require).
// The first argument is the target's seed folder: missing or empty, the
// replay fails (2), as libFuzzer does in the sanitizer stage, so that a
// target whose seeds went missing is not a pass in the Release stage; a
// regression corpus after it may not exist yet.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  std::vector<std::filesystem::path> files;
  if (argc < 2 || !std::filesystem::is_directory(argv[1]) ||
      std::filesystem::is_empty(argv[1])) {
    std::fprintf(stderr, "replay: the seed folder %s is missing or empty\n",
                 argc < 2 ? "(none named)" : argv[1]);
    return 2;
  }
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path p = argv[i];
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(p)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
    } else if (std::filesystem::is_regular_file(p)) {
      files.push_back(p);
    } else {
      // A regression corpus that has no input yet.
      std::fprintf(stderr, "replay: %s does not exist, skipped\n", argv[i]);
    }
  }
  for (const auto& f : files) {
    // Exactly the input's size, so that ASan sees any overrun. (A sized
    // read: GCC 12 warns of a null dereference inside istreambuf_iterator.)
    std::vector<uint8_t> copy(std::filesystem::file_size(f));
    std::ifstream in(f, std::ios::binary);
    in.read(reinterpret_cast<char*>(copy.data()), static_cast<std::streamsize>(copy.size()));
    if (!in) {
      std::fprintf(stderr, "replay: cannot read %s\n", f.c_str());
      return 1;
    }
    LLVMFuzzerTestOneInput(copy.data(), copy.size());
  }
  std::printf("replay: %zu inputs ran\n", files.size());
  return files.empty() ? 2 : 0;
}
