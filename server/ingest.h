// Atomic ingest into the catalog: keep the original (original_store.h),
// encode it (remeshing irregular input as `meshwave encode` does), write
// its container content-addressed and durably, then insert the row. A
// crash at any point leaves either nothing, or files the catalog does not
// know (removed by RemoveOrphans), never a row without its files.
#ifndef MESHWAVE_SERVER_INGEST_H_
#define MESHWAVE_SERVER_INGEST_H_

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "catalog.h"
#include "encode_settings.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "original_store.h"

namespace meshwave::server {

struct IngestResult {
  CatalogEntry entry;
  bool already_present = false;  // the same mesh was in the catalog
  bool remeshed = false;
  // With a fidelity asked for: the complete stream's symmetric surface PSNR
  // against the mesh as uploaded (meshwave/fidelity.h); 0 otherwise.
  double fidelity_db = 0;
};

// A container made from an original, not yet stored.
struct EncodedMesh {
  std::string container;
  StreamHeader header;
  size_t packets = 0;
  bool remeshed = false;
  double fidelity_db = 0;  // as IngestResult's
};

// Reads the original as an asset (untrusted bytes; the format from the main
// file's extension; sidecar files among `parts`) and encodes it through the
// asset pipeline (meshwave/asset_encoder.h: remeshed when needed, vertex
// colours carried) as `choices` say, under the name `name`. What the
// stream leaves out is logged as a warning. kParseError or
// kInvalidArgument for a mesh that cannot be read or remeshed.
Result<EncodedMesh> EncodeOriginal(const std::vector<OriginalPart>& parts, const std::string& main,
                                   const std::string& name, const EncodeChoices& choices);

// The catalog entry of `encoded` (id, container path, statistics; not
// its original or settings).
CatalogEntry EntryFor(const EncodedMesh& encoded);

// Ingests an original: `parts` are the mesh file named `main` and its
// sidecar files. The mesh's id comes from the original, the settings and
// the name (MeshIdOf): when the catalog has it already, nothing is encoded
// and the existing entry is returned.
Result<IngestResult> IngestOriginal(Catalog& catalog, const std::vector<OriginalPart>& parts,
                                    const std::string& main, const std::string& name,
                                    const EncodeChoices& choices = {});

// One mesh file held in memory, named `source` (its extension gives the
// format: .ply, .obj, .off, .glb, .gltf).
Result<IngestResult> IngestMeshBytes(Catalog& catalog, std::string_view bytes,
                                     const std::string& name, const std::string& source,
                                     const EncodeChoices& choices = {});

// Reads a mesh file (format from its extension) and ingests it with the
// files beside it that it refers to (a .gltf's buffers and images, an
// .obj's material libraries and textures); `name` empty: the file's stem.
Result<IngestResult> IngestMeshFile(Catalog& catalog, const std::filesystem::path& path,
                                    const std::string& name = "",
                                    const EncodeChoices& choices = {});

// Stores a complete container as it is (checked with ParseContainer and
// ValidateStreamHeader first: kParseError when it is not one), with no
// original: it cannot be re-encoded. Its id is its SHA-256's; identical
// bytes give the existing entry.
Result<IngestResult> IngestContainer(Catalog& catalog, std::string container,
                                     const std::string& name, const std::string& source);

struct CleanupReport {
  size_t orphan_files = 0;      // containers no row refers to
  size_t temp_files = 0;        // left by an interrupted write
  size_t orphan_originals = 0;  // original files no original lists
  size_t expired_containers = 0;  // retired containers past their time
};

// How long a container replaced by a re-encode stays on disk for the
// readers that may still open it (other replicas, a request in flight
// on a server that has not yet seen the swap).
inline constexpr int64_t kDefaultRetiredSeconds = 3600;

// Forgets the retired containers older than `retired_seconds`, then
// removes every file in STORE/containers/ and STORE/originals/ that the
// catalog does not refer to. Holds the ingest lock, so it never races a
// concurrent ingest.
Result<CleanupReport> RemoveOrphans(Catalog& catalog,
                                    int64_t retired_seconds = kDefaultRetiredSeconds);

// Deletes an entry: the row first, then its container, and its original's
// files once no other mesh uses them (a crash in between leaves orphan
// files, never a row without its files). False: no such id.
Result<bool> RemoveEntry(Catalog& catalog, const std::string& id);

// Seconds since the epoch.
int64_t NowUnix();

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_INGEST_H_
