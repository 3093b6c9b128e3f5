#include "original_store.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "core/durable_file.h"
#include "sha256.h"

namespace meshwave::server {
namespace {

constexpr size_t kMaxNameBytes = 200;

}  // namespace

Status CheckOriginalFileName(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameBytes) {
    return InvalidArgument("a file name must have 1 to " + std::to_string(kMaxNameBytes) +
                           " bytes");
  }
  for (char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\') {
      return InvalidArgument("file name '" + std::string(name) +
                             "' holds a control character or a backslash");
    }
  }
  size_t start = 0;
  while (start <= name.size()) {
    const size_t end = std::min(name.find('/', start), name.size());
    const std::string_view segment = name.substr(start, end - start);
    if (segment.empty() || segment == "." || segment == "..") {
      return InvalidArgument("file name '" + std::string(name) +
                             "' must be a relative path without empty, '.' or '..' parts");
    }
    start = end + 1;
  }
  return Status::Ok();
}

Result<Original> DescribeOriginal(const std::vector<OriginalPart>& parts,
                                  const std::string& main) {
  Original o;
  std::set<std::string_view> names;
  for (const OriginalPart& p : parts) {
    MW_RETURN_IF_ERROR(CheckOriginalFileName(p.name));
    if (!names.insert(p.name).second) {
      return InvalidArgument("file '" + p.name + "' given twice");
    }
    o.files.push_back({p.name, Sha256Hex(p.bytes), p.bytes.size()});
    o.bytes += p.bytes.size();
  }
  if (!names.count(main)) return InvalidArgument("the main file '" + main + "' is not among the files");
  std::sort(o.files.begin(), o.files.end(),
            [](const OriginalFile& a, const OriginalFile& b) { return a.name < b.name; });
  o.main = main;
  const size_t dot = main.rfind('.');
  o.format = dot == std::string::npos ? "" : main.substr(dot + 1);
  std::transform(o.format.begin(), o.format.end(), o.format.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  o.digest = Sha256Hex(ManifestText(o));
  return o;
}

std::string ManifestText(const Original& o) {
  std::string text = "meshwave-original 1\nmain " + o.main + "\nformat " + o.format + "\n";
  for (const OriginalFile& f : o.files) {
    text += f.sha256 + " " + std::to_string(f.bytes) + " " + f.name + "\n";
  }
  return text;
}

std::filesystem::path OriginalBlobPath(const std::filesystem::path& store_dir,
                                       std::string_view sha256) {
  return store_dir / "originals" / std::string(sha256);
}

Status WriteOriginal(const std::filesystem::path& store_dir, const Original& original,
                     const std::vector<OriginalPart>& parts) {
  std::error_code ec;
  std::filesystem::create_directories(store_dir / "originals", ec);
  if (ec) {
    return IoError("cannot create " + (store_dir / "originals").string() + ": " + ec.message());
  }
  for (const OriginalPart& p : parts) {
    const auto f = std::find_if(original.files.begin(), original.files.end(),
                                [&](const OriginalFile& o) { return o.name == p.name; });
    if (f == original.files.end()) return Status(StatusCode::kInternal, "original: unknown part " + p.name);
    const auto path = OriginalBlobPath(store_dir, f->sha256);
    // Content-addressed: a blob of the right size is this content (a
    // damaged one is found when it is read back, and rewritten by the next
    // ingest of the same bytes only once it is removed).
    if (std::filesystem::file_size(path, ec) == f->bytes && !ec) continue;
    MW_RETURN_IF_ERROR(WriteFileDurably(path, p.bytes));
  }
  return Status::Ok();
}

Result<std::string> ReadOriginalFile(const std::filesystem::path& store_dir,
                                     const OriginalFile& file) {
  const auto path = OriginalBlobPath(store_dir, file.sha256);
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError("original file " + file.name + " (" + path.string() + ") is missing");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) return IoError("cannot read " + path.string());
  std::string out = std::move(bytes).str();
  if (out.size() != file.bytes || Sha256Hex(out) != file.sha256) {
    return IoError("original file " + file.name + " (" + path.string() +
                   ") is damaged: its content no longer matches its digest");
  }
  return out;
}

}  // namespace meshwave::server
