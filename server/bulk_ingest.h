// Ingest at scale: the mesh files of folders and lists, split into shards
// (one per worker of a Kubernetes Job) and encoded by parallel threads
// into one catalog. Each file is an ordinary atomic ingest (ingest.h), so
// a rerun, or two workers given the same file, only find their container
// already present.
#ifndef MESHWAVE_SERVER_BULK_INGEST_H_
#define MESHWAVE_SERVER_BULK_INGEST_H_

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "catalog.h"
#include "ingest.h"

namespace meshwave::server {

// The mesh files (.ply, .obj, .off, .glb, .gltf, any case) named by `inputs` (files, or
// folders searched recursively) and by `list_file` (one path per line,
// relative to the list's folder; blank lines and '#' comments skipped;
// empty: none), sorted, each once. kNotFound for a missing input.
Result<std::vector<std::filesystem::path>> CollectMeshFiles(
    const std::vector<std::string>& inputs, const std::string& list_file);

struct Shard {
  uint32_t index = 0;  // 0 .. count-1
  uint32_t count = 1;
};
// "I/N" with I < N (e.g. "3/8"). kInvalidArgument otherwise.
Result<Shard> ParseShard(const std::string& text);

// Whether `key` (a file's path, a mesh id) falls in `shard`: its FNV-1a
// hash modulo the count is the index, so it depends on the key alone.
bool InShard(const std::string& key, Shard shard);

// The files of `shard`: those whose path is InShard, so a file's shard
// depends on its path alone, not on what else is listed.
std::vector<std::filesystem::path> FilesOfShard(const std::vector<std::filesystem::path>& files,
                                                Shard shard);

// Ingests `files` with `jobs` threads, encoded as `choices` says; `name`
// names the entry (one file only; empty: the stem). With choices.threads
// 0, each file in flight gets the machine's cores divided by the files
// encoded at once (at least one), so jobs x threads stays near the cores. `report` runs after
// each file, one call at a time. Returns how many files failed.
size_t IngestFiles(Catalog& catalog, const std::vector<std::filesystem::path>& files,
                   unsigned jobs, const std::string& name,
                   const std::function<void(const std::filesystem::path&,
                                            const Result<IngestResult>&)>& report,
                   const EncodeChoices& choices = {});

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_BULK_INGEST_H_
