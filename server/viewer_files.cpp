#include "viewer_files.h"

#include <array>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <system_error>
#include <utility>

#include "etag.h"
#include "meshwave/request_target.h"
#include "response.h"
#include "sha256.h"

namespace meshwave::server {
namespace {

constexpr std::string_view kPrefix = "/viewer";
// Viewer files are small (the largest, three.js's core, is 1.5 MB); a
// bigger one is not ours.
constexpr uintmax_t kMaxFileBytes = 16u << 20;

std::string_view PathOf(std::string_view target) {
  return target.substr(0, target.find('?'));
}

Response Redirect(std::string location) {
  Response r{http::status::moved_permanently, 11};
  r.set(http::field::location, location);
  r.set(http::field::cache_control, "no-cache");
  return r;
}

bool Inside(const std::filesystem::path& root,
            const std::filesystem::path& file) {
  auto r = root.begin();
  auto f = file.begin();
  for (; r != root.end(); ++r, ++f) {
    if (f == file.end() || *r != *f) return false;
  }
  return true;
}

// A viewer file as last read, with its ETag: a page load revalidates every
// file, and hashing three.js (1.5 MB) again for each 304 would cost more
// than the request.
struct CachedFile {
  std::filesystem::file_time_type mtime;
  uintmax_t size = 0;
  std::string body;
  std::string etag;
};

// The file's content and ETag, read again when its time or size changed;
// null when it cannot be read.
std::shared_ptr<const CachedFile> ReadCached(const std::filesystem::path& file,
                                             uintmax_t size) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::shared_ptr<const CachedFile>>
      files;
  std::error_code ec;
  const auto mtime = std::filesystem::last_write_time(file, ec);
  if (ec) return nullptr;
  {
    const std::scoped_lock lock(mutex);
    const auto it = files.find(file);
    if (it != files.end() && it->second->mtime == mtime &&
        it->second->size == size) {
      return it->second;
    }
  }
  auto cached = std::make_shared<CachedFile>();
  cached->mtime = mtime;
  cached->size = size;
  cached->body.resize(static_cast<size_t>(size));
  std::ifstream in(file, std::ios::binary);
  if (!in.read(cached->body.data(),
               static_cast<std::streamsize>(cached->body.size()))) {
    return nullptr;
  }
  cached->etag = StrongEtag(Sha256Hex(cached->body), "");
  const std::scoped_lock lock(mutex);
  files[file] = cached;
  return cached;
}

}  // namespace

bool IsViewerTarget(std::string_view target) {
  const std::string_view path = PathOf(target);
  return path == kPrefix ||
         (path.starts_with(kPrefix) && path[kPrefix.size()] == '/');
}

std::string_view ViewerContentType(const std::filesystem::path& file) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 9>
      kTypes = {{
          {".html", "text/html; charset=utf-8"},
          {".js", "text/javascript; charset=utf-8"},
          {".mjs", "text/javascript; charset=utf-8"},
          {".css", "text/css; charset=utf-8"},
          {".wasm", "application/wasm"},
          {".json", "application/json"},
          {".png", "image/png"},
          {".svg", "image/svg+xml"},
          {".txt", "text/plain; charset=utf-8"},
      }};
  const std::string ext = file.extension().string();
  for (const auto& [e, type] : kTypes) {
    if (ext == e) return type;
  }
  return "application/octet-stream";
}

std::filesystem::path DefaultViewerDir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed =
        exe.parent_path().parent_path() / "share" / "meshwave" / "viewer";
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  return MESHWAVE_BUILD_VIEWER_DIR;
}

Response ServeViewerFile(const ServerContext& ctx, const Request& req) {
  const std::string_view target = req.target();
  const std::string_view path = PathOf(target);
  if (req.method() != http::verb::get && req.method() != http::verb::head) {
    Response r =
        JsonError(http::status::method_not_allowed, "method not allowed here");
    r.set(http::field::allow, "GET, HEAD");
    return r;
  }
  // Relative links in index.html need the trailing slash.
  if (path == kPrefix) return Redirect("/viewer/");
  const std::string_view rest =
      path.substr(kPrefix.size());  // "/", "/viewer.js", ...
  std::vector<std::string> segments;
  if (rest != "/") {
    // The same checks as every other target: no "..", no encoded slash.
    auto parsed = ParseRequestTarget(rest);
    if (!parsed.ok()) return StatusError(parsed.status());
    segments = std::move(parsed->segments);
  }
  if (segments.empty()) segments.push_back("index.html");

  std::error_code ec;
  const std::filesystem::path root =
      std::filesystem::canonical(ctx.config().viewer_dir(), ec);
  if (ec) {
    return JsonError(
        http::status::not_found,
        "the viewer is not installed here (meshwave-server --viewer-dir DIR)");
  }
  std::filesystem::path file = root;
  for (const auto& s : segments) file /= s;
  file = std::filesystem::canonical(file, ec);
  if (ec || !Inside(root, file) ||
      !std::filesystem::is_regular_file(file, ec)) {
    return JsonError(http::status::not_found, "no such viewer file");
  }
  const uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxFileBytes)
    return JsonError(http::status::not_found, "no such viewer file");
  const auto cached = ReadCached(file, size);
  if (cached == nullptr) {
    return JsonError(http::status::internal_server_error,
                     "cannot read a viewer file");
  }
  Response r{http::status::ok, 11};
  const auto inm = req[http::field::if_none_match];
  if (!inm.empty() && IfNoneMatchMatches(inm, cached->etag)) {
    r.result(http::status::not_modified);
  } else {
    r.set(http::field::content_type, ViewerContentType(file));
    r.body().owned = cached->body;
  }
  r.set(http::field::etag, cached->etag);
  r.set(http::field::cache_control, "no-cache");
  r.set("X-Content-Type-Options", "nosniff");
  return r;
}

}  // namespace meshwave::server
