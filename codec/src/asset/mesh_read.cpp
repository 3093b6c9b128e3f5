// ReadMesh and ParseMesh (meshwave/mesh_io.h): whole-file reads and the
// parser dispatch. PLY, OBJ and OFF go to the geometry readers (mesh/),
// glTF to the asset reader without its images; so this file sits above
// both, in asset/, and is compiled into meshwave_codec (codec/asset.cmake).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "asset/asset_readers.h"
#include "mesh/mesh_readers.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"

namespace meshwave {
namespace {

// Larger inputs are refused before reading: the biggest meshes we handle are
// a few hundred MB, and every reader needs a few times the file in memory.
constexpr uint64_t kMaxFileBytes = uint64_t{4} << 30;

Status ErrnoError(const std::filesystem::path& path, const char* action,
                  int error) {
  return IoError(path.string() + ": cannot " + action + ": " +
                 std::strerror(error));
}

// Closes a file descriptor on every path out of a function.
class FdCloser {
 public:
  explicit FdCloser(int fd) : fd_(fd) {}
  FdCloser(const FdCloser&) = delete;
  FdCloser& operator=(const FdCloser&) = delete;
  ~FdCloser() {
    if (fd_ >= 0) ::close(fd_);
  }
 private:
  int fd_;
};

// The files beside a glTF given as bytes alone: none.
class NoOtherFiles final : public FileSet {
 public:
  explicit NoOtherFiles(std::string_view name) : name_(name) {}
  Result<std::string_view> Read(std::string_view file) override {
    return Status(StatusCode::kNotFound,
                  name_ + " refers to " + std::string(file) +
                      ", which is not available here (read the file from its "
                      "folder: ReadMesh, or ParseMeshAsset with its files)");
  }
  bool Contains(std::string_view) const override { return false; }
  std::string Describe() const override { return "no files"; }

 private:
  std::string name_;
};

Result<TriMesh> GltfGeometry(std::string_view bytes, FileSet& files,
                             std::string_view name) {
  GltfReadOptions options;
  options.load_images = false;
  MW_ASSIGN_OR_RETURN(MeshAsset asset,
                      ParseGltfAsset(bytes, files, name, AssetLimits{}, options));
  return std::move(asset.mesh);
}

}  // namespace

Result<TriMesh> ParseMesh(std::string_view bytes, MeshFormat format,
                          std::string_view name) {
  Result<TriMesh> mesh = [&]() -> Result<TriMesh> {
    switch (format) {
      case MeshFormat::kPly:
        return ParsePly(bytes, name);
      case MeshFormat::kObj:
        return ParseObj(bytes, name);
      case MeshFormat::kOff:
        return ParseOff(bytes, name);
      case MeshFormat::kGltf: {
        NoOtherFiles none(std::string{name});
        return GltfGeometry(bytes, none, name);
      }
    }
    return InvalidArgument(std::string(name) + ": unknown mesh format");
  }();
  if (mesh.ok() && mesh->faces.empty()) {
    return ParseError(std::string(name) + ": no faces (" +
                      std::to_string(mesh->positions.size()) + " vertices)");
  }
  return mesh;
}

Result<TriMesh> ReadMesh(const std::filesystem::path& path) {
  MW_ASSIGN_OR_RETURN(MeshFormat format, FormatFromPath(path));
  if (format == MeshFormat::kGltf) {
    // A .gltf's buffers are files beside it: read through the folder.
    DirectoryFileSet files(path.has_parent_path() ? path.parent_path()
                                                  : std::filesystem::path("."));
    const std::string name = path.filename().string();
    MW_ASSIGN_OR_RETURN(const std::string_view bytes, files.Read(name));
    MW_ASSIGN_OR_RETURN(TriMesh mesh, GltfGeometry(bytes, files, name));
    return mesh;
  }
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return ErrnoError(path, "open", errno);
  FdCloser closer(fd);
  struct stat info {};
  if (::fstat(fd, &info) != 0) return ErrnoError(path, "stat", errno);
  if (!S_ISREG(info.st_mode))
    return IoError(path.string() + ": not a regular file");
  const uint64_t size = static_cast<uint64_t>(info.st_size);
  if (size > kMaxFileBytes) {
    return IoError(path.string() + ": " + std::to_string(size) +
                   " bytes is larger than the 4 GiB limit");
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (got < 0) {
      if (errno == EINTR) continue;
      return ErrnoError(path, "read", errno);
    }
    if (got == 0) {
      return IoError(path.string() + ": file shrank while being read");
    }
    done += static_cast<size_t>(got);
  }
  return ParseMesh(bytes, format, path.string());
}

}  // namespace meshwave
