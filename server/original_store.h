// The originals: what users uploaded and what an ingest read, kept in the
// store beside the containers (STORE/originals/<sha256>, one file per
// distinct content) so that a container can be made again from it, e.g. by
// `meshwave-server reencode` when the stream format changes. An original
// is a set of files (a mesh and its sidecar files: material library,
// images); it is named by the digest of its manifest, so the same files
// under the same names are stored once however often they are ingested.
#ifndef MESHWAVE_SERVER_ORIGINAL_STORE_H_
#define MESHWAVE_SERVER_ORIGINAL_STORE_H_

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::server {

struct OriginalFile {
  std::string name;    // relative path, as the mesh file names it ("cow.mtl", "tex/a.png")
  std::string sha256;  // of its bytes: its blob is STORE/originals/<sha256>
  uint64_t bytes = 0;
};

struct Original {
  std::string digest;  // SHA-256 of ManifestText(*this)
  std::string main;    // the file a reader opens (one of `files`)
  std::string format;  // its extension, lower case: "ply", "obj", "off", ...
  uint64_t bytes = 0;  // sum of the files'
  std::vector<OriginalFile> files;  // by name, each name once
};

// A file of an original as it arrives: its name and bytes.
struct OriginalPart {
  std::string name;
  std::string_view bytes;
};

// Checks a file name of an original: 1 to 200 bytes of relative path
// ('/'-separated, no empty, "." or ".." segment, no backslash, no control
// character). kInvalidArgument saying what is wrong.
Status CheckOriginalFileName(std::string_view name);

// The Original of `parts` (their names checked, each once), `main` being
// one of them. Computes every digest; writes nothing.
Result<Original> DescribeOriginal(const std::vector<OriginalPart>& parts, const std::string& main);

// "meshwave-original 1", "main NAME", "format F", then "SHA256 BYTES NAME"
// per file by name: the text whose SHA-256 is the original's digest.
std::string ManifestText(const Original& original);

// Where the blob of a file with this digest lives.
std::filesystem::path OriginalBlobPath(const std::filesystem::path& store_dir,
                                       std::string_view sha256);

// Writes the blobs of `parts` that the store does not hold yet (durably:
// temporary file, fsync, rename, directory fsync). `original` must be
// DescribeOriginal(parts, ...).
Status WriteOriginal(const std::filesystem::path& store_dir, const Original& original,
                     const std::vector<OriginalPart>& parts);

// Reads one file of an original back and checks it against its digest:
// IoError naming the file when its blob is missing, unreadable or damaged.
Result<std::string> ReadOriginalFile(const std::filesystem::path& store_dir,
                                     const OriginalFile& file);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_ORIGINAL_STORE_H_
