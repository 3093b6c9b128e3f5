// The encoder settings a catalog records beside each container, as one
// line of text, so that `meshwave-server reencode` can make the container
// again from the mesh's original with the same choices (or tell which
// meshes were made with other ones). The text is canonical: the same
// choices always give the same bytes, and it is part of a new mesh's id.
#ifndef MESHWAVE_SERVER_ENCODE_SETTINGS_H_
#define MESHWAVE_SERVER_ENCODE_SETTINGS_H_

#include <string>
#include <string_view>

#include "meshwave/encoder.h"
#include "meshwave/fidelity.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave::server {

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
  // Bounds on what reading the original may take (an upload's are lowered
  // from the server's configuration: UploadAssetLimits). Like threads, not
  // part of the settings text: they refuse inputs, never change a container.
  AssetLimits limits;
  // When the original's attributes cannot be read but its geometry can:
  // store the geometry alone (a warning says so) instead of refusing it.
  // Off for ingests and uploads unless asked; on for re-encodes, whose
  // originals an earlier version accepted. Not part of the settings text.
  bool allow_geometry_only = false;
  // End the stream in the original mesh (docs/FORMAT.md 2.5; `--no-original`
  // leaves it out). In the settings text as "original=no" when off, so that
  // the default's text is the one earlier versions wrote.
  bool original_layer = true;
};

// "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=4096 split=48":
// the choices that change the container (threads do not). Numbers in their
// shortest round-tripping form.
std::string FormatEncodeSettings(const EncodeChoices& choices);

// Reads what FormatEncodeSettings wrote: every key once, in any order.
// kInvalidArgument, naming the key or value at fault, otherwise. Threads
// stay at their default.
Result<EncodeChoices> ParseEncodeSettings(std::string_view text);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_ENCODE_SETTINGS_H_
