#include "meshwave/client/local_state.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "client_state.pb.h"
#include "meshwave/container.h"

namespace meshwave::client {
namespace {

constexpr uint32_t kStateVersion = 1;
constexpr uintmax_t kMaxStateBytes = uintmax_t{1} << 32;

Status Errno(const std::string& what, const std::filesystem::path& path) {
  return IoError(what + " " + path.string() + ": " + std::strerror(errno));
}

// Writes `bytes` to a temporary file beside `path`, fsyncs it and renames it
// over `path`, then fsyncs the directory: a crash leaves the old file or the
// new one, never half of one.
Status WriteAtomically(const std::filesystem::path& path,
                       std::string_view bytes) {
  const std::filesystem::path tmp =
      path.string() + ".tmp-" + std::to_string(::getpid());
  const int fd =
      ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Errno("cannot create", tmp);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      Status s = Errno("cannot write", tmp);
      ::close(fd);
      ::unlink(tmp.c_str());
      return s;
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    Status s = Errno("cannot flush", tmp);
    ::unlink(tmp.c_str());
    return s;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    Status s = Errno("cannot rename to", path);
    ::unlink(tmp.c_str());
    return s;
  }
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return Status::Ok();
}

Result<std::string> ReadAll(const std::filesystem::path& path) {
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return IoError("cannot read " + path.string() + ": " + ec.message());
  if (size > kMaxStateBytes)
    return ParseError(path.string() + ": too large for a state file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  if (!in && !in.eof()) return IoError("cannot read " + path.string());
  return out.str();
}

}  // namespace

std::filesystem::path SidecarPath(const std::filesystem::path& file) {
  return file.string() + ".session";
}

std::string SessionBytes(const LocalState& state) {
  proto::ClientState meta;
  meta.set_version(kStateVersion);
  meta.set_mesh_url(state.url.ToString());
  meta.set_order(ProgressionName(state.order));
  meta.set_max_level(state.max_level);
  meta.set_cursor(state.cursor);
  meta.set_budget_bytes(state.budget_bytes);
  return meta.SerializeAsString();
}

Status SaveState(const std::filesystem::path& file, const LocalState& state) {
  MW_RETURN_IF_ERROR(WriteAtomically(file, state.container));
  return WriteAtomically(SidecarPath(file), SessionBytes(state));
}

Result<LocalState> LoadState(const std::filesystem::path& file) {
  MW_ASSIGN_OR_RETURN(std::string meta_bytes, ReadAll(SidecarPath(file)));
  MW_ASSIGN_OR_RETURN(std::string container, ReadAll(file));
  return ParseState(meta_bytes, std::move(container), file);
}

Result<LocalState> ParseState(std::string_view session, std::string container,
                              const std::filesystem::path& file) {
  const std::filesystem::path sidecar = SidecarPath(file);
  auto refuse = [&](const std::filesystem::path& which,
                    const std::string& why) {
    return ParseError("state " + which.string() + ": " + why);
  };
  proto::ClientState meta;
  if (!meta.ParseFromArray(session.data(), static_cast<int>(session.size())))
    return refuse(sidecar, "does not parse");
  if (meta.version() != kStateVersion) {
    return refuse(sidecar, "version " + std::to_string(meta.version()) +
                               " (expected " + std::to_string(kStateVersion) +
                               ")");
  }
  LocalState state;
  auto url = ParseMeshUrl(meta.mesh_url());
  if (!url.ok()) return refuse(sidecar, url.status().message());
  state.url = std::move(*url);
  auto order = ParseProgression(meta.order());
  if (!order.ok()) return refuse(sidecar, order.status().message());
  state.order = *order;
  if (meta.max_level() < -1 || meta.max_level() > 12) {
    return refuse(sidecar, "max_level " + std::to_string(meta.max_level()) +
                               " out of range");
  }
  state.max_level = meta.max_level();
  state.budget_bytes = meta.budget_bytes();

  state.container = std::move(container);
  auto parsed = ParseContainer(state.container);
  if (!parsed.ok()) return refuse(file, parsed.status().message());
  if (meta.cursor() != parsed->ids.size()) {
    return refuse(file, "holds " + std::to_string(parsed->ids.size()) +
                            " packets but " + sidecar.string() + " says " +
                            std::to_string(meta.cursor()) +
                            " (the two files do not belong together)");
  }
  state.cursor = parsed->ids.size();
  return state;
}

}  // namespace meshwave::client
