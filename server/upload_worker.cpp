#include "upload_worker.h"

#include <spdlog/spdlog.h>

#include <charconv>

#include "upload_files.h"

namespace meshwave::server {

std::string FormatUploadOutcome(const Result<IngestResult>& result) {
  if (!result.ok()) {
    std::string message = result.status().message();
    for (char& c : message) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    return "error " + std::to_string(static_cast<int>(result.status().code())) + " " + message +
           "\n";
  }
  char fidelity[32];
  const auto end = std::to_chars(fidelity, fidelity + sizeof fidelity, result->fidelity_db).ptr;
  return "id " + result->entry.id + "\nalready_present " + (result->already_present ? "1" : "0") +
         "\nremeshed " + (result->remeshed ? "1" : "0") + "\nfidelity_db " +
         std::string(fidelity, end) + "\n";
}

Result<UploadOutcome> ParseUploadOutcome(std::string_view text) {
  const auto unreadable = [&] {
    return Status(StatusCode::kInternal,
                  "the upload worker's answer is unreadable: '" +
                      std::string(text.substr(0, 200)) + "'");
  };
  if (text.starts_with("error ")) {
    std::string_view rest = text.substr(6);
    int code = 0;
    const auto r = std::from_chars(rest.data(), rest.data() + rest.size(), code);
    if (r.ec != std::errc() || code <= 0 || code > static_cast<int>(StatusCode::kInternal) ||
        r.ptr == rest.data() + rest.size() || *r.ptr != ' ') {
      return unreadable();
    }
    std::string_view message = rest.substr(static_cast<size_t>(r.ptr - rest.data()) + 1);
    if (message.ends_with('\n')) message.remove_suffix(1);
    return Status(static_cast<StatusCode>(code), std::string(message));
  }
  UploadOutcome o;
  int seen = 0;
  size_t i = 0;
  while (i < text.size()) {
    const size_t end = std::min(text.find('\n', i), text.size());
    const std::string_view line = text.substr(i, end - i);
    i = end + 1;
    const size_t space = line.find(' ');
    if (space == std::string_view::npos) return unreadable();
    const std::string_view key = line.substr(0, space), value = line.substr(space + 1);
    if (key == "id") {
      o.id = std::string(value);
      seen |= 1;
    } else if (key == "already_present" || key == "remeshed") {
      if (value != "0" && value != "1") return unreadable();
      (key == "remeshed" ? o.remeshed : o.already_present) = value == "1";
      seen |= key == "remeshed" ? 2 : 4;
    } else if (key == "fidelity_db") {
      const auto r = std::from_chars(value.data(), value.data() + value.size(), o.fidelity_db);
      if (r.ec != std::errc()) return unreadable();
      seen |= 8;
    } else {
      return unreadable();
    }
  }
  if (seen != 15) return unreadable();
  return o;
}

Result<IngestResult> IngestUpload(Catalog& catalog, std::string_view body, const std::string& name,
                                  const std::string& source, const std::string& boundary,
                                  const EncodeChoices& choices) {
  if (boundary.empty()) {
    // One file alone cannot bring the files it names (an .obj's material
    // library, a .gltf's external buffers or images): what it holds of its
    // own is stored, and the log says what was not sent.
    EncodeChoices alone = choices;
    alone.allow_geometry_only = true;
    return IngestMeshBytes(catalog, body, name, source, alone);
  }
  MW_ASSIGN_OR_RETURN(UploadFiles files, FilesOfMultipart(body, boundary, source));
  return IngestOriginal(catalog, files.parts, files.main, name, choices);
}

Result<UploadOutcome> IngestInWorker(const std::string& catalog,
                                     const std::filesystem::path& store, std::string_view bytes,
                                     const std::string& name, const std::string& source,
                                     const std::string& boundary, const EncodeChoices& choices,
                                     const WorkerOptions& options) {
  std::vector<std::string> args = {"ingest-upload", "--catalog", catalog, "--name", name,
                                   "--source", source};
  if (!store.empty()) args.insert(args.end(), {"--store", store.string()});
  // "--boundary=B": a boundary may begin with dashes.
  if (!boundary.empty()) args.push_back("--boundary=" + boundary);
  args.insert(args.end(), {"--fidelity", std::to_string(choices.fidelity_db),
                           "--max-vertex-ratio", std::to_string(choices.max_vertex_ratio),
                           "--threads", std::to_string(choices.threads),
                           "--max-file-bytes", std::to_string(choices.limits.max_file_bytes),
                           "--max-image-bytes", std::to_string(choices.limits.max_image_bytes),
                           "--max-image-pixels", std::to_string(choices.limits.max_image_pixels)});
  MW_ASSIGN_OR_RETURN(WorkerResult run, RunWorker(args, bytes, options));
  // The worker's own log lines (remesh warnings, fidelity reached) go to
  // the server's log.
  size_t i = 0;
  while (i < run.err.size()) {
    const size_t end = std::min(run.err.find('\n', i), run.err.size());
    const std::string_view line = std::string_view(run.err).substr(i, end - i);
    // At the level the worker logged it (what the stream leaves out is a warning).
    if (line.find("] [warning] ") != std::string_view::npos) {
      spdlog::warn("upload {}: {}", name, line);
    } else if (end > i) {
      spdlog::info("upload {}: {}", name, line);
    }
    i = end + 1;
  }
  if (run.exit_code != 0 && run.exit_code != 3) {
    return Status(StatusCode::kInternal,
                  "the ingest worker " + DescribeExit(run.exit_code) +
                      (run.exit_code == -9 ? " (out of memory?)" : ""));
  }
  return ParseUploadOutcome(run.out);
}

}  // namespace meshwave::server
