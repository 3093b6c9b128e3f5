#include "reencode.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "core/durable_file.h"
#include "ingest.h"
#include "meshwave/container.h"
#include "meshwave/stream_header.h"
#include "meshwave/stream_limits.h"

namespace meshwave::server {
namespace {

// The stream format version of a stored container, read from its header
// alone (a version this build no longer decodes still tells its number).
Result<uint32_t> StoredFormatVersion(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError("cannot read " + path.string());
  std::string head(kContainerPreambleBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  MW_ASSIGN_OR_RETURN(const uint32_t length, ReadContainerHeaderLength(head));
  if (length > kMaxHeaderBytes) return ParseError(path.string() + ": header too long");
  std::string header(length, '\0');
  in.read(header.data(), static_cast<std::streamsize>(length));
  if (!in) return ParseError(path.string() + ": cut inside its header");
  MW_ASSIGN_OR_RETURN(StreamHeader h, ReadStreamHeader(header));
  return h.format_version;
}

// Encodes `entry` again from its original with `choices` and swaps the new
// container in. kChanged when the row moved on meanwhile.
Result<ReencodeStep> Reencode(Catalog& catalog, const CatalogEntry& entry,
                              const EncodeChoices& choices) {
  ReencodeStep step;
  step.before = entry;
  MW_ASSIGN_OR_RETURN(auto original, catalog.FindOriginal(entry.original));
  if (!original) {
    return Status(StatusCode::kNotFound, "the catalog lists no original " + entry.original);
  }
  std::vector<std::string> bytes;
  bytes.reserve(original->files.size());
  for (const OriginalFile& f : original->files) {
    MW_ASSIGN_OR_RETURN(std::string b, ReadOriginalFile(catalog.store_dir(), f));
    bytes.push_back(std::move(b));
  }
  std::vector<OriginalPart> parts;
  for (size_t i = 0; i < bytes.size(); ++i) parts.push_back({original->files[i].name, bytes[i]});
  // The catalog accepted this original once (an earlier version may have
  // kept its geometry alone): it stays servable even if its attributes
  // still cannot be read.
  EncodeChoices lenient = choices;
  lenient.allow_geometry_only = true;
  MW_ASSIGN_OR_RETURN(EncodedMesh encoded,
                      EncodeOriginal(parts, original->main, entry.name, lenient));
  CatalogEntry now = EntryFor(encoded);
  now.id = entry.id;
  now.settings = FormatEncodeSettings(choices);
  {
    MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
    MW_RETURN_IF_ERROR(WriteFileDurably(catalog.ContainerPath(now), encoded.container));
    MW_ASSIGN_OR_RETURN(const bool swapped,
                        catalog.ReplaceContainer(entry.id, entry.sha256, now, NowUnix()));
    if (!swapped) {
      step.action = ReencodeAction::kChanged;
      step.why = "deleted or changed by another process meanwhile";
      // The file is an orphan unless a row names it: RemoveOrphans decides.
      return step;
    }
  }
  MW_ASSIGN_OR_RETURN(auto after, catalog.Find(entry.id));
  step.after = after.value_or(now);
  step.action = ReencodeAction::kReencoded;
  return step;
}

}  // namespace

EncodeChoices SettingsChange::ApplyTo(EncodeChoices c) const {
  if (fidelity_db) c.fidelity_db = *fidelity_db;
  if (max_vertex_ratio) c.max_vertex_ratio = *max_vertex_ratio;
  if (force_remesh) c.force_remesh = *force_remesh;
  if (precinct_coefficients) c.precinct_coefficients = *precinct_coefficients;
  if (split_bytes_per_precinct) c.split_bytes_per_precinct = *split_bytes_per_precinct;
  return c;
}

Result<ReencodeReport> ReencodeCatalog(
    Catalog& catalog, const ReencodeOptions& options,
    const std::function<void(size_t, size_t, const ReencodeStep&)>& progress) {
  MW_ASSIGN_OR_RETURN(const uint64_t count, catalog.Count());
  MW_ASSIGN_OR_RETURN(std::vector<CatalogEntry> all, catalog.List(count, 0));
  std::vector<CatalogEntry> entries;
  for (CatalogEntry& e : all) {
    if (InShard(e.id, options.shard)) entries.push_back(std::move(e));
  }
  ReencodeReport report;
  report.meshes = entries.size();
  for (size_t i = 0; i < entries.size(); ++i) {
    const CatalogEntry& e = entries[i];
    const auto start = std::chrono::steady_clock::now();
    ReencodeStep step;
    step.before = e;
    uint32_t version = e.format_version;
    if (version == 0) {
      auto read = StoredFormatVersion(catalog.ContainerPath(e));
      if (read.ok()) version = *read;
    }
    auto recorded = e.settings.empty() ? Result<EncodeChoices>(EncodeChoices{})
                                       : ParseEncodeSettings(e.settings);
    if (e.original.empty()) {
      step.action = version == kStreamFormatVersion ? ReencodeAction::kCurrent
                                                    : ReencodeAction::kNoOriginal;
      step.why = "no original kept (ingested before originals were kept, or as a ready "
                 "container): ingest it again from its file";
    } else if (!recorded.ok()) {
      step.action = ReencodeAction::kFailed;
      step.why = recorded.status().message();
    } else {
      EncodeChoices choices = options.change.ApplyTo(*recorded);
      choices.threads = options.threads;
      const std::string wanted = FormatEncodeSettings(choices);
      std::string why;
      if (version != kStreamFormatVersion) {
        why = "format version " + std::to_string(version) + " -> " +
              std::to_string(kStreamFormatVersion);
      }
      if (wanted != e.settings) {
        why += (why.empty() ? "" : ", ") + std::string("settings '") + e.settings + "' -> '" +
               wanted + "'";
      }
      if (why.empty()) {
        step.action = ReencodeAction::kCurrent;
      } else if (options.dry_run) {
        step.action = ReencodeAction::kWouldReencode;
        step.why = why;
      } else {
        auto done = Reencode(catalog, e, choices);
        if (done.ok()) {
          step = std::move(*done);
          if (step.why.empty()) step.why = why;
        } else {
          step.action = ReencodeAction::kFailed;
          step.why = done.status().ToString();
        }
      }
    }
    switch (step.action) {
      case ReencodeAction::kCurrent: ++report.current; break;
      case ReencodeAction::kReencoded: ++report.reencoded; break;
      case ReencodeAction::kWouldReencode: ++report.reencoded; break;
      case ReencodeAction::kNoOriginal: ++report.no_original; break;
      case ReencodeAction::kChanged: ++report.changed; break;
      case ReencodeAction::kFailed: ++report.failed; break;
    }
    step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(i, entries.size(), step);
  }
  return report;
}

}  // namespace meshwave::server
