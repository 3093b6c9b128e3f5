// Atomic ingest into the catalog: encode a mesh (remeshing irregular input
// as `meshwave encode` does), write its container content-addressed and
// durably, then insert the row. A crash at any point leaves either nothing,
// or a file the catalog does not know (removed by RemoveOrphans), never a
// row without its file.
#ifndef MESHWAVE_SERVER_INGEST_H_
#define MESHWAVE_SERVER_INGEST_H_

#include <filesystem>
#include <string>
#include <string_view>

#include "catalog.h"
#include "meshwave/encoder.h"
#include "meshwave/fidelity.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/status.h"

namespace meshwave::server {

struct IngestResult {
  CatalogEntry entry;
  bool already_present = false;  // same container was in the catalog
  bool remeshed = false;
  // With a fidelity asked for: the complete stream's symmetric surface PSNR
  // against the mesh as uploaded (meshwave/fidelity.h); 0 otherwise.
  double fidelity_db = 0;
};

// How a mesh is encoded at ingest: the defaults, or denser and finer until
// the complete stream reaches `fidelity_db` against the mesh as uploaded
// (meshwave/fidelity.h), with at most `max_vertex_ratio` finest vertices
// per input vertex.
struct EncodeChoices {
  // 0: one remesh at about the input's density, the default precision.
  double fidelity_db = kDefaultFidelityDb;
  double max_vertex_ratio = kDefaultMaxVertexRatio;
  // Threads for remeshing and encoding the one mesh (0: the machine's
  // cores); the container does not depend on it.
  int threads = 0;
  // Remesh even a mesh that is already semi-regular (`meshwave encode
  // --remesh`).
  bool force_remesh = false;
  // Precincts (`meshwave encode --precinct-size`, `--split-bytes`): base
  // faces grouped into runs of at least this many coefficients per subband
  // so that region requests can refine one part first; 0: none.
  uint32_t precinct_coefficients = EncodeOptions{}.precinct_coefficients;
  uint32_t split_bytes_per_precinct = EncodeOptions{}.split_bytes_per_precinct;
};

// Stores a complete container (checked with ParseContainer and
// ValidateStreamHeader first: kParseError when it is not one). Identical
// bytes give the existing entry.
Result<IngestResult> IngestContainer(Catalog& catalog, std::string container,
                                     const std::string& name,
                                     const std::string& source);

// Parses mesh file bytes (untrusted), makes them semi-regular, encodes them
// with the default options and stores the container. kParseError or
// kInvalidArgument for a mesh that cannot be read or remeshed.
Result<IngestResult> IngestMeshBytes(Catalog& catalog, std::string_view bytes,
                                     MeshFormat format, const std::string& name,
                                     const std::string& source,
                                     const EncodeChoices& choices = {});

// Reads a mesh file (format from its extension) and ingests it; `name`
// empty: the file's stem.
Result<IngestResult> IngestMeshFile(Catalog& catalog,
                                    const std::filesystem::path& path,
                                    const std::string& name = "",
                                    const EncodeChoices& choices = {});

struct CleanupReport {
  size_t orphan_files = 0;  // containers no row refers to
  size_t temp_files = 0;    // left by an interrupted write
};

// Removes every file in DIR/containers/ that no catalog row refers to.
// Holds the ingest lock, so it never races a concurrent ingest.
Result<CleanupReport> RemoveOrphans(Catalog& catalog);

// Deletes an entry: the row first, then its file (a crash in between
// leaves an orphan file, never a row without a file). False: no such id.
Result<bool> RemoveEntry(Catalog& catalog, const std::string& id);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_INGEST_H_
