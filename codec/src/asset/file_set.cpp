#include "meshwave/file_set.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace meshwave {
namespace {

// A name quoted for a message: control bytes shown as '?', long names cut.
std::string QuotedName(std::string_view name) {
  constexpr size_t kMaxShown = 80;
  std::string out = "\"";
  for (size_t i = 0; i < name.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    out += c < 0x20 || c == 0x7f ? '?' : static_cast<char>(c);
  }
  if (name.size() > kMaxShown) out += "...";
  return out + "\"";
}

Status NameError(std::string_view name, const char* why) {
  return InvalidArgument("file name " + QuotedName(name) + " " + why);
}

Status NotFound(const std::string& message) {
  return Status(StatusCode::kNotFound, message);
}

// Splits a '/'-separated path into its segments (empty ones included).
std::vector<std::string_view> Segments(std::string_view path) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t slash = path.find('/', start);
    out.push_back(path.substr(start, slash == std::string_view::npos
                                         ? std::string_view::npos
                                         : slash - start));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  return out;
}

bool HasControlByte(std::string_view s) {
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return true;
  }
  return false;
}

// "C:" or "c:/": a drive letter, which a relative name never starts with.
bool HasDriveLetter(std::string_view s) {
  return s.size() >= 2 && s[1] == ':' &&
         ((s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z'));
}

// "http:", "file:", "data:": a URI scheme (RFC 3986: a letter, then letters,
// digits, '+', '-' or '.', then ':'). Drive letters are caught before.
bool HasUriScheme(std::string_view s) {
  const size_t colon = s.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  for (size_t i = 0; i < colon; ++i) {
    const char c = s[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    const bool other =
        (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
    if (!alpha && !(i > 0 && other)) return false;
  }
  return true;
}

}  // namespace

Status CheckFileSetName(std::string_view name) {
  if (name.empty()) return InvalidArgument("empty file name");
  if (HasControlByte(name)) return NameError(name, "contains a control byte");
  if (name.find('\\') != std::string_view::npos) {
    return NameError(name, "contains a backslash (use '/' between folders)");
  }
  if (name.front() == '/' || HasDriveLetter(name)) {
    return NameError(name, "is absolute (names are relative to the upload)");
  }
  for (std::string_view segment : Segments(name)) {
    if (segment.empty()) return NameError(name, "has an empty path segment");
    if (segment == "." || segment == "..") {
      return NameError(name, "has a \".\" or \"..\" segment");
    }
  }
  return Status::Ok();
}

Result<std::string> ResolveFileSetReference(std::string_view referrer,
                                            std::string_view reference) {
  auto refuse = [&](const char* why) {
    return InvalidArgument(QuotedName(referrer) + " refers to " +
                           QuotedName(reference) + ", which " + why);
  };
  if (reference.empty()) return refuse("is empty");
  if (HasControlByte(reference)) return refuse("contains a control byte");
  if (reference.find('\\') != std::string_view::npos) {
    return refuse("contains a backslash");
  }
  if (reference.front() == '/' || HasDriveLetter(reference)) {
    return refuse("is an absolute path (only files beside it can be read)");
  }
  if (HasUriScheme(reference)) {
    return refuse("is a URI with a scheme (only files beside it can be read)");
  }
  std::vector<std::string_view> out = Segments(referrer);
  out.pop_back();  // the referrer's own name: keep its folder
  for (std::string_view segment : Segments(reference)) {
    if (segment.empty() || segment == ".") continue;
    if (segment == "..") {
      if (out.empty()) return refuse("leaves the folder of the upload");
      out.pop_back();
      continue;
    }
    out.push_back(segment);
  }
  if (out.empty()) return refuse("names no file");
  std::string joined;
  for (std::string_view segment : out) {
    if (!joined.empty()) joined += '/';
    joined += segment;
  }
  return joined;
}

DirectoryFileSet::DirectoryFileSet(std::filesystem::path root,
                                   uint64_t max_total_bytes)
    : root_(std::move(root)), max_total_bytes_(max_total_bytes) {}

std::string DirectoryFileSet::Describe() const { return root_.string(); }

Result<std::filesystem::path> DirectoryFileSet::Locate(
    std::string_view name) const {
  MW_RETURN_IF_ERROR(CheckFileSetName(name));
  const std::filesystem::path path = root_ / std::string(name);
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path, ec);
  if (ec) {
    return NotFound(path.string() + ": not found (" + ec.message() + ")");
  }
  const std::filesystem::path real_root = std::filesystem::canonical(root_, ec);
  if (ec) return IoError(root_.string() + ": " + ec.message());
  // A symbolic link may point anywhere: the target must stay under the root.
  const std::string prefix = real_root.string() + "/";
  if (real.string().compare(0, prefix.size(), prefix) != 0) {
    return InvalidArgument(path.string() + " leads outside " + root_.string() +
                           " (a symbolic link)");
  }
  if (!std::filesystem::is_regular_file(real, ec)) {
    return NotFound(path.string() + ": not a regular file");
  }
  return real;
}

bool DirectoryFileSet::Contains(std::string_view name) const {
  return Locate(name).ok();
}

Result<std::string_view> DirectoryFileSet::Read(std::string_view name) {
  if (auto it = cache_.find(name); it != cache_.end()) {
    return std::string_view(*it->second);
  }
  MW_ASSIGN_OR_RETURN(const std::filesystem::path path, Locate(name));
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    return IoError(path.string() + ": cannot open: " + std::strerror(errno));
  }
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    return IoError(path.string() + ": cannot stat: " + std::strerror(errno));
  }
  const uint64_t size = static_cast<uint64_t>(info.st_size);
  if (size > max_total_bytes_ - total_bytes_) {
    return InvalidArgument(path.string() + ": " + std::to_string(size) +
                           " bytes would take the files of one mesh past " +
                           std::to_string(max_total_bytes_) + " bytes");
  }
  auto bytes = std::make_unique<std::string>(static_cast<size_t>(size), '\0');
  size_t done = 0;
  while (done < bytes->size()) {
    const ssize_t got = ::read(fd, bytes->data() + done, bytes->size() - done);
    if (got < 0) {
      if (errno == EINTR) continue;
      return IoError(path.string() + ": cannot read: " + std::strerror(errno));
    }
    if (got == 0) {
      return IoError(path.string() + ": file shrank while being read");
    }
    done += static_cast<size_t>(got);
  }
  total_bytes_ += size;
  const std::string_view view = *bytes;
  cache_.emplace(std::string(name), std::move(bytes));
  return view;
}

Status MemoryFileSet::Add(std::string_view name, std::string bytes) {
  MW_RETURN_IF_ERROR(CheckFileSetName(name));
  if (files_.count(name) != 0) {
    return InvalidArgument("file " + QuotedName(name) + " given twice");
  }
  if (bytes.size() > max_total_bytes_ - total_bytes_) {
    return InvalidArgument("file " + QuotedName(name) + ": " +
                           std::to_string(bytes.size()) +
                           " bytes would take the files of one mesh past " +
                           std::to_string(max_total_bytes_) + " bytes");
  }
  total_bytes_ += bytes.size();
  files_.emplace(std::string(name), std::move(bytes));
  return Status::Ok();
}

Result<std::string_view> MemoryFileSet::Read(std::string_view name) {
  MW_RETURN_IF_ERROR(CheckFileSetName(name));
  const auto it = files_.find(name);
  if (it == files_.end()) {
    return NotFound("file " + QuotedName(name) + " is not in the upload");
  }
  return std::string_view(it->second);
}

bool MemoryFileSet::Contains(std::string_view name) const {
  return CheckFileSetName(name).ok() && files_.count(name) != 0;
}

}  // namespace meshwave
