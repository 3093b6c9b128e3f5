#include "bulk_ingest.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include "core/parallel_for.h"
#include "meshwave/request_target.h"

namespace meshwave::server {
namespace {

bool IsMeshFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".glb" || ext == ".gltf";
}

Status AddInput(const std::filesystem::path& input, std::set<std::filesystem::path>& out) {
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec)) {
    for (std::filesystem::recursive_directory_iterator it(input, ec), end; !ec && it != end;
         it.increment(ec)) {
      if (it->is_regular_file(ec) && IsMeshFile(it->path())) out.insert(it->path());
    }
    if (ec) return IoError("cannot list " + input.string() + ": " + ec.message());
    return Status::Ok();
  }
  if (!std::filesystem::is_regular_file(input, ec)) {
    return Status(StatusCode::kNotFound, "no such mesh file or folder: " + input.string());
  }
  out.insert(input);
  return Status::Ok();
}

uint64_t Fnv1a(const std::string& s) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

Result<std::vector<std::filesystem::path>> CollectMeshFiles(
    const std::vector<std::string>& inputs, const std::string& list_file) {
  std::set<std::filesystem::path> files;
  for (const auto& input : inputs) MW_RETURN_IF_ERROR(AddInput(input, files));
  if (!list_file.empty()) {
    std::ifstream in(list_file);
    if (!in) return IoError("cannot read list " + list_file);
    const std::filesystem::path base = std::filesystem::path(list_file).parent_path();
    std::string line;
    while (std::getline(in, line)) {
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
      if (line.empty() || line[0] == '#') continue;
      const std::filesystem::path p(line);
      MW_RETURN_IF_ERROR(AddInput(p.is_absolute() ? p : base / p, files).WithContext(list_file));
    }
  }
  return std::vector<std::filesystem::path>(files.begin(), files.end());
}

Result<Shard> ParseShard(const std::string& text) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return InvalidArgument("shard '" + text + "' is not I/N");
  auto index = ParseUnsigned(text.substr(0, slash), UINT32_MAX, "shard index");
  auto count = ParseUnsigned(text.substr(slash + 1), UINT32_MAX, "shard count");
  if (!index.ok() || !count.ok() || *count == 0 || *index >= *count) {
    return InvalidArgument("shard '" + text + "' is not I/N with 0 <= I < N");
  }
  return Shard{static_cast<uint32_t>(*index), static_cast<uint32_t>(*count)};
}

bool InShard(const std::string& key, Shard shard) {
  return Fnv1a(key) % shard.count == shard.index;
}

std::vector<std::filesystem::path> FilesOfShard(const std::vector<std::filesystem::path>& files,
                                                Shard shard) {
  std::vector<std::filesystem::path> out;
  for (const auto& f : files) {
    if (InShard(f.string(), shard)) out.push_back(f);
  }
  return out;
}

size_t IngestFiles(Catalog& catalog, const std::vector<std::filesystem::path>& files,
                   unsigned jobs, const std::string& name,
                   const std::function<void(const std::filesystem::path&,
                                            const Result<IngestResult>&)>& report,
                   const EncodeChoices& choices) {
  const unsigned n = std::max(1u, std::min<unsigned>(jobs, static_cast<unsigned>(files.size())));
  // Each of the n meshes in flight gets its share of the cores unless told
  // otherwise, so --jobs does not multiply the threads.
  EncodeChoices per_file = choices;
  if (per_file.threads <= 0) {
    per_file.threads = std::max(1, ResolveThreads(0) / static_cast<int>(n));
  }
  std::atomic<size_t> next{0}, failed{0};
  std::mutex report_mutex;
  // Encoding runs in parallel; each Store takes the catalog's ingest lock
  // only around the write and the insert.
  auto worker = [&] {
    for (size_t i = next++; i < files.size(); i = next++) {
      auto result = IngestMeshFile(catalog, files[i], name, per_file);
      if (!result.ok()) ++failed;
      std::lock_guard lock(report_mutex);
      report(files[i], result);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned t = 1; t < n; ++t) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  return failed.load();
}

}  // namespace meshwave::server
