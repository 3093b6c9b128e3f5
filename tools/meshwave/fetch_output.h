// What `meshwave fetch` and `meshwave refine` show and write while a
// session refines a mesh: a progress line on a terminal, one mesh per
// refinement in --lods, the surface PSNR against --reference, the final mesh
// and a summary (text or --json).
#ifndef MESHWAVE_TOOLS_FETCH_OUTPUT_H_
#define MESHWAVE_TOOLS_FETCH_OUTPUT_H_

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli_util.h"
#include "client_state.pb.h"
#include "meshwave/client/session.h"
#include "meshwave/mesh.h"

namespace meshwave::cli {

struct FetchOutputOptions {
  std::string out;        // final mesh (.ply, .obj, .glb, .gltf; colours but in .obj)
  std::string lods;       // directory for one mesh per refinement, or empty
  std::string reference;  // original mesh for the surface PSNR, or empty
  bool json = false;
  int extra_levels = kDefaultExtraLevels;
  int max_level = -1;
};

// Registers --out (with `out_help`; required when `out_required`), --lods,
// --reference, --extra-levels and --json on a command that refines a mesh.
void AddFetchOutputOptions(CLI::App* cmd, FetchOutputOptions& options,
                           const std::string& out_help, bool out_required);

class FetchOutput {
 public:
  // Reads the reference and creates the --lods directory.
  static Result<std::unique_ptr<FetchOutput>> Create(
      const FetchOutputOptions& options);

  // The session's progress handler. Failures to write a LOD are kept and
  // returned by Finish (a handler cannot stop the session).
  client::ProgressHandler Handler();

  // Writes the final mesh and prints the summary. `state` names the state
  // file written, if any.
  Status Finish(const client::Session& session, const std::string& url,
                const std::string& state);
  // The same for any session: `order` as the report names it, `counted`
  // what p.packets counts ("packets in quality order", "units, region
  // first").
  Status Finish(const ProgressiveDecoder* decoder, const client::Progress& p,
                const std::string& order, const std::string& counted, const std::string& url,
                const std::string& state);

 private:
  explicit FetchOutput(FetchOutputOptions options)
      : options_(std::move(options)) {}
  double SurfacePsnr(const ProgressiveDecoder& decoder) const;
  // The mesh written (with its colours) and measured (OutputLevel).
  DecodedMesh OutputMesh(const ProgressiveDecoder& decoder) const;
  void OnProgress(const client::Progress& p, const ProgressiveDecoder& decoder);

  FetchOutputOptions options_;
  std::optional<TriMesh> reference_;
  bool terminal_ = false;
  bool line_open_ = false;
  Status lod_error_;
  proto::FetchReport report_;
  std::chrono::steady_clock::time_point start_ =
      std::chrono::steady_clock::now();
};

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_FETCH_OUTPUT_H_
