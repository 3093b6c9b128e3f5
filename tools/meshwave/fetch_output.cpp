#include "fetch_output.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli_util.h"
#include "meshwave/mesh_io.h"
#include "meshwave/metrics.h"

namespace meshwave::cli {

void AddFetchOutputOptions(CLI::App* cmd, FetchOutputOptions& options,
                           const std::string& out_help, bool out_required) {
  CLI::Option* out = cmd->add_option("--out", options.out, out_help);
  if (out_required) out->required();
  cmd->add_option("--lods", options.lods,
                  "Directory for one mesh per refinement (lod_NNNN.ply)");
  cmd->add_option("--reference", options.reference,
                  "Original mesh (the one uploaded): print at every step the "
                  "PSNR of the symmetric surface distance to it, as "
                  "`meshwave compare ORIGINAL DECODED` gives it");
  cmd->add_option("--extra-levels", options.extra_levels, kExtraLevelsHelp)
      ->check(CLI::Range(0, kMaxStreamLevels))
      ->capture_default_str();
  cmd->add_flag("--json", options.json,
                "Print one JSON object (steps, bytes, PSNR, timings)");
}
namespace {

double MsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now() - t)
      .count();
}

std::string HumanBytes(uint64_t n) {
  char buf[32];
  if (n < 10 * 1024) {
    std::snprintf(buf, sizeof buf, "%llu B",
                  static_cast<unsigned long long>(n));
  } else if (n < 10 * 1024 * 1024) {
    std::snprintf(buf, sizeof buf, "%.1f KiB", static_cast<double>(n) / 1024);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f MiB",
                  static_cast<double>(n) / (1024 * 1024));
  }
  return buf;
}

std::string Db(double db) {
  if (std::isinf(db)) return "lossless";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f dB", db);
  return buf;
}

// ", textured: 448 x 448 (level 2 of 3)" for the base colour map (or the
// first map) held; ", texture not received yet" before its first level.
std::string TextureHeld(const ProgressiveDecoder& decoder, const DecodedMesh& decoded) {
  if (!decoded.textured || decoder.texture().maps.empty()) return "";
  if (decoded.images.empty()) return ", texture not received yet";
  const TextureImage* image = &decoded.images.front();
  for (const TextureImage& held : decoded.images) {
    if (held.role == TextureRole::kBaseColor) image = &held;
  }
  size_t levels = 0;
  for (const TextureMapInfo& map : decoder.texture().maps) {
    if (map.role == image->role) levels = map.levels.size();
  }
  char line[96];
  std::snprintf(line, sizeof line, ", textured: %u x %u (level %d of %zu)", image->width,
                image->height, image->level + 1, levels);
  return line;
}

}  // namespace

Result<std::unique_ptr<FetchOutput>> FetchOutput::Create(
    const FetchOutputOptions& options) {
  std::unique_ptr<FetchOutput> out(new FetchOutput(options));
  if (!options.reference.empty()) {
    MW_ASSIGN_OR_RETURN(TriMesh ref, ReadMesh(options.reference));
    out->reference_ = std::move(ref);
  }
  if (!options.lods.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.lods, ec);
    if (ec)
      return IoError("cannot create " + options.lods + ": " + ec.message());
  }
  out->terminal_ = !options.json && ::isatty(STDERR_FILENO) == 1;
  return out;
}

// The distance a user judges a decoded mesh by: to the surface they
// uploaded, both ways (a remeshed stream has other vertices than the
// original, so no vertex-to-vertex matching measures it).
double FetchOutput::SurfacePsnr(const ProgressiveDecoder& decoder) const {
  if (!reference_) return 0;
  auto d = SymmetricSurfaceDistance(*reference_, OutputMesh(decoder).mesh);
  return d.ok() ? d->PsnrDb(d->rms) : 0;
}

DecodedMesh FetchOutput::OutputMesh(const ProgressiveDecoder& decoder) const {
  return DecodeLevel(decoder, OutputLevel(decoder, options_.max_level, options_.extra_levels));
}

void FetchOutput::OnProgress(const client::Progress& p,
                             const ProgressiveDecoder& decoder) {
  if (report_.steps_size() == 0) report_.set_first_mesh_ms(MsSince(start_));
  proto::FetchStep* step = report_.add_steps();
  step->set_packets(p.packets);
  step->set_bytes(p.bytes);
  step->set_level(p.level);
  step->set_estimated_psnr_db(p.estimated_psnr_db);
  if (reference_) step->set_true_psnr_db(SurfacePsnr(decoder));
  if (!options_.lods.empty() && lod_error_.ok()) {
    char name[32];
    std::snprintf(name, sizeof name, "lod_%04zu.ply", p.packets);
    const std::string path =
        (std::filesystem::path(options_.lods) / name).string();
    lod_error_ = WriteDecodedMesh(OutputMesh(decoder), path);
    step->set_lod_file(path);
  }
  step->set_elapsed_ms(MsSince(start_));
  if (terminal_) {
    std::fprintf(stderr, "\r%10s  %5zu/%zu packets  level %d/%d  PSNR %s",
                 HumanBytes(p.bytes).c_str(), p.packets, p.order_packets,
                 p.level, p.levels, Db(p.estimated_psnr_db).c_str());
    if (reference_)
      std::fprintf(stderr, " (surface %s)", Db(step->true_psnr_db()).c_str());
    if (p.retries > 0) std::fprintf(stderr, "  %d retries", p.retries);
    std::fprintf(stderr, "\033[K");
    std::fflush(stderr);
    line_open_ = true;
  }
}

client::ProgressHandler FetchOutput::Handler() {
  return [this](const client::Progress& p, const ProgressiveDecoder& d) {
    OnProgress(p, d);
  };
}

Status FetchOutput::Finish(const client::Session& session,
                           const std::string& url, const std::string& state) {
  const char* order = ProgressionName(session.options().order);
  return Finish(session.decoder(), session.progress(), order,
                std::string("packets in ") + order + " order", url, state);
}

Status FetchOutput::Finish(const ProgressiveDecoder* decoder, const client::Progress& p,
                           const std::string& order, const std::string& counted,
                           const std::string& url, const std::string& state) {
  if (line_open_) std::fprintf(stderr, "\n");
  line_open_ = false;
  MW_RETURN_IF_ERROR(lod_error_);
  if (decoder == nullptr)
    return Status(StatusCode::kInternal, "no stream header received");
  const DecodedMesh decoded = OutputMesh(*decoder);
  const TriMesh& mesh = decoded.mesh;
  if (!options_.out.empty()) MW_RETURN_IF_ERROR(WriteDecodedMesh(decoded, options_.out));

  report_.set_mesh_url(url);
  report_.set_order(order);
  report_.set_max_level(options_.max_level);
  report_.set_packets(p.packets);
  report_.set_packets_total(p.order_packets);
  report_.set_bytes(p.bytes);
  report_.set_received_bytes(p.received_bytes);
  report_.set_packets_received(p.packets_received);
  report_.set_level(p.level);
  report_.set_levels(p.levels);
  report_.set_estimated_psnr_db(p.estimated_psnr_db);
  if (reference_) report_.set_true_psnr_db(SurfacePsnr(*decoder));
  report_.set_complete(p.complete());
  report_.set_retries(static_cast<uint32_t>(p.retries));
  report_.set_output(options_.out);
  report_.set_state(state);
  report_.set_vertices(mesh.positions.size());
  report_.set_faces(mesh.faces.size());
  report_.set_elapsed_ms(MsSince(start_));
  if (options_.json) {
    PrintJson(report_);
    return Status::Ok();
  }
  if (!options_.out.empty()) {
    std::printf(
        "wrote %s: %zu vertices, %zu faces (complete levels %d of %d)%s%s\n",
        options_.out.c_str(), mesh.positions.size(), mesh.faces.size(), p.level,
        p.levels, decoded.colors.empty() ? "" : ", with vertex colours",
        TextureHeld(*decoder, decoded).c_str());
  }
  std::printf(
      "%zu of %zu %s, %llu bytes (%llu received), estimated "
      "PSNR %s (against the encoded mesh)",
      p.packets, p.order_packets, counted.c_str(),
      static_cast<unsigned long long>(p.bytes),
      static_cast<unsigned long long>(p.received_bytes),
      Db(p.estimated_psnr_db).c_str());
  if (reference_)
    std::printf(", surface PSNR %s against %s",
                Db(report_.true_psnr_db()).c_str(), options_.reference.c_str());
  std::printf("\n");
  if (!state.empty())
    std::printf("state in %s (refine with: meshwave refine %s --more SIZE)\n",
                state.c_str(), state.c_str());
  return Status::Ok();
}

}  // namespace meshwave::cli
