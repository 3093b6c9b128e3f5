// FileSet: the files one mesh asset is made of (a .gltf and its .bin and
// images, an .obj with its .mtl and textures), found by relative name. Two
// kinds: a folder on disk (command-line input) and names mapped to bytes in
// memory (an upload). Both refuse a name that could leave the set (see
// CheckFileSetName) and bound the bytes they hand out, so a reader that
// follows references found in untrusted files can reach nothing else.
#ifndef MESHWAVE_FILE_SET_H_
#define MESHWAVE_FILE_SET_H_

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave {

// Names in a file set are relative, '/'-separated paths: "a.gltf",
// "textures/wood.png". Refused, with kInvalidArgument and a message naming
// the reason: empty names, absolute paths ("/x", "C:..."), backslashes,
// "." or ".." segments, empty segments ("a//b"), NUL or other control bytes.
Status CheckFileSetName(std::string_view name);

// Resolves `reference` (a relative path found in `referrer`, e.g. an image
// URI in a .gltf or a map_Kd in an .mtl) against the folder of `referrer`
// within the set: "models/a.gltf" + "../tex/b.png" = "tex/b.png". `.` and
// `..` segments are folded; a result that would leave the set's root, an
// absolute reference, a URI with a scheme ("http:", "file:") or a backslash
// is refused (kInvalidArgument), naming both.
Result<std::string> ResolveFileSetReference(std::string_view referrer,
                                            std::string_view reference);

class FileSet {
 public:
  // Default cap on the bytes one set hands out in total (all files read).
  static constexpr uint64_t kDefaultMaxTotalBytes = uint64_t{4} << 30;

  virtual ~FileSet() = default;

  // The bytes of the file `name` (checked by CheckFileSetName), valid as
  // long as this set lives. kNotFound names the file when it is absent;
  // kIoError when the system refuses the read; kInvalidArgument when the
  // file would take the set past its byte budget. Reading a file twice
  // costs its bytes once.
  virtual Result<std::string_view> Read(std::string_view name) = 0;

  // Whether `name` is a valid name of a file in the set (reads nothing).
  virtual bool Contains(std::string_view name) const = 0;

  // What the set is, for messages: the folder, or "upload".
  virtual std::string Describe() const = 0;
};

// The files of one folder (and its subfolders). Symbolic links are followed
// only when their target stays inside the folder.
class DirectoryFileSet final : public FileSet {
 public:
  explicit DirectoryFileSet(std::filesystem::path root,
                            uint64_t max_total_bytes = kDefaultMaxTotalBytes);

  Result<std::string_view> Read(std::string_view name) override;
  bool Contains(std::string_view name) const override;
  std::string Describe() const override;

 private:
  // The path of `name` under the root, or an error when it is not a regular
  // file inside it.
  Result<std::filesystem::path> Locate(std::string_view name) const;

  std::filesystem::path root_;
  uint64_t max_total_bytes_;
  uint64_t total_bytes_ = 0;
  std::map<std::string, std::unique_ptr<std::string>, std::less<>> cache_;
};

// Files held in memory, name -> bytes (an upload's parts, a zip's entries).
class MemoryFileSet final : public FileSet {
 public:
  explicit MemoryFileSet(uint64_t max_total_bytes = kDefaultMaxTotalBytes)
      : max_total_bytes_(max_total_bytes) {}

  // Adds a file. kInvalidArgument for a bad or repeated name, or when the
  // set would hold more than its byte budget.
  Status Add(std::string_view name, std::string bytes);

  Result<std::string_view> Read(std::string_view name) override;
  bool Contains(std::string_view name) const override;
  std::string Describe() const override { return "upload"; }

 private:
  uint64_t max_total_bytes_;
  uint64_t total_bytes_ = 0;
  std::map<std::string, std::string, std::less<>> files_;
};

}  // namespace meshwave

#endif  // MESHWAVE_FILE_SET_H_
