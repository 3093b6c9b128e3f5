#include "meshwave/progressive_decoder.h"

#include <cmath>
#include <limits>
#include <string>

#include "bitplane/bitplane_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "core/parallel_for.h"
#include "meshwave/progression.h"
#include "meshwave/semiregular.h"
#include "meshwave/wavelet.h"
#include "quant/deadzone_quantizer.h"
#include "stream/base_mesh_codec.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "stream/sawt_field.h"
#include "stream/stream_format.h"

namespace meshwave {

struct ProgressiveDecoder::Impl {
  StreamHeader header;
  DecoderOptions options;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  std::unique_ptr<WaveletTransform> transform;
  DecodedBase base;
  std::vector<SubbandLayout> layouts;
  std::vector<std::array<ComponentState, 3>> states;
  std::vector<char> have;
  std::unique_ptr<PacketLayout> packets;
  DistortionEstimates estimates;
  std::vector<double> chain_now;  // each chain's estimated term now
  size_t decoded = 0;
  uint64_t bytes = 0;
  double distortion = 0;
  bool broken = false;
  double diagonal = 0;

  bool parent_contexts() const { return header.coder == StreamCoder::k3xC; }
};

ProgressiveDecoder::ProgressiveDecoder(std::unique_ptr<Impl> impl)
    : impl_(std::move(impl)) {}
ProgressiveDecoder::~ProgressiveDecoder() = default;

Result<std::unique_ptr<ProgressiveDecoder>> ProgressiveDecoder::Create(
    const StreamHeader& header, const DecoderOptions& options) {
  MW_RETURN_IF_ERROR(ValidateStreamHeader(header));
  if (header.faces > options.max_faces) {
    return Status(StatusCode::kUnsupported,
                  "header: " + std::to_string(header.faces) +
                      " faces, more than this decoder's limit of " +
                      std::to_string(options.max_faces));
  }
  auto impl = std::make_unique<Impl>();
  impl->header = header;
  impl->header.present.clear();
  impl->options = options;
  MW_ASSIGN_OR_RETURN(TransformSettings settings,
                      SetUpHierarchy(header, options.max_base_vertices, impl->base,
                                     impl->hierarchy));
  const auto& h = *impl->hierarchy;
  impl->diagonal = HeaderDiagonal(header);
  // The octrees and the transform's stencils are the two big parts of the
  // set-up (about a quarter and two thirds of it on igea) and independent.
  Result<WaveletTransform> transform = InvalidArgument("not built");
  ParallelInvoke(
      options.threads,
      [&] { transform = WaveletTransform::Create(impl->hierarchy, settings); },
      [&] { impl->layouts = BuildSubbandLayouts(h, impl->base.grid, header.octree_leaf_size); });
  if (!transform.ok()) return transform.status();
  impl->transform = std::make_unique<WaveletTransform>(std::move(*transform));
  impl->packets = std::make_unique<PacketLayout>(header);
  impl->estimates = ReadDistortionIndex(header, PacketChains(header));
  std::unique_ptr<ProgressiveDecoder> decoder(new ProgressiveDecoder(std::move(impl)));
  decoder->Reset();
  return decoder;
}

void ProgressiveDecoder::Reset() {
  Impl& m = *impl_;
  const int levels = static_cast<int>(m.layouts.size());
  m.states.resize(levels);  // Init reuses the lists' memory
  for (int j = 0; j < levels; ++j) {
    for (int c = 0; c < 3; ++c) {
      m.states[j][c].Init(m.layouts[j].tree,
                          m.header.quantizer(j, c).top_bitplane);
    }
  }
  m.have.assign(m.header.packets.length.size(), 0);
  m.chain_now = m.estimates.chain_start;
  m.distortion = m.estimates.start();
  m.decoded = 0;
  m.bytes = 0;
  m.broken = false;
}

const StreamHeader& ProgressiveDecoder::header() const { return impl_->header; }
size_t ProgressiveDecoder::packet_count() const { return impl_->have.size(); }
bool ProgressiveDecoder::HasPacket(uint32_t id) const {
  return id < impl_->have.size() && impl_->have[id];
}
size_t ProgressiveDecoder::packets_decoded() const { return impl_->decoded; }
uint64_t ProgressiveDecoder::payload_bytes_decoded() const { return impl_->bytes; }

bool ProgressiveDecoder::DependenciesMet(uint32_t id) const {
  if (id >= impl_->have.size()) return false;
  for (uint32_t d : impl_->packets->Dependencies(id, impl_->parent_contexts())) {
    if (!impl_->have[d]) return false;
  }
  return true;
}

Status ProgressiveDecoder::AddPacket(uint32_t id, std::string_view payload) {
  Impl& m = *impl_;
  if (m.broken) {
    return Status(StatusCode::kInvalidArgument,
                  "decoder is unusable after an earlier corrupt packet");
  }
  if (id >= m.have.size()) {
    return InvalidArgument("packet " + std::to_string(id) + " is not in the index of " +
                           std::to_string(m.have.size()) + " packets");
  }
  const auto& index = m.header.packets;
  const int j = m.packets->Subband(id);
  const int b = m.packets->Bitplane(id);
  // The packet's name, for errors only: built on the way out (it was a
  // tenth of a small packet's decoding time).
  auto what = [&] {
    return "packet " + std::to_string(id) + " (subband " + std::to_string(j) + ", bitplane " +
           std::to_string(b) + ")";
  };
  if (m.have[id]) return InvalidArgument(what() + " was already added");
  for (uint32_t d : m.packets->Dependencies(id, m.parent_contexts())) {
    if (!m.have[d]) {
      return InvalidArgument(what() + " needs packet " + std::to_string(d) + " (subband " +
                             std::to_string(m.packets->Subband(d)) + ", bitplane " +
                             std::to_string(m.packets->Bitplane(d)) + ") first");
    }
  }
  if (payload.size() != index.length[id]) {
    return ParseError(what() + ": " + std::to_string(payload.size()) + " bytes, index says " +
                      std::to_string(index.length[id]));
  }
  if (!PacketCheckMatches(index, id, payload)) {
    return ParseError(what() + ": CRC-16 check mismatch (corrupt payload)");
  }
  DecoderIo io(payload);
  const SubbandLayout& layout = m.layouts[j];
  ComponentContexts contexts;  // shared by the packet's three components
  for (int c = 0; c < 3; ++c) {
    ComponentState& s = m.states[j][c];
    if (b > s.top) continue;
    ParentView parent;
    if (m.parent_contexts() && j > 0) {
      parent = {layout.parent_position, m.states[j - 1][c].mag, m.states[j - 1][c].negative};
    }
    CodeBitplane(layout.tree, s, b, parent, contexts, io);
  }
  if (io.decoder().overrun()) {
    m.broken = true;
    return ParseError(what() + ": payload ends before its symbols (corrupt stream)");
  }
  m.have[id] = 1;
  ++m.decoded;
  m.bytes += payload.size();
  // A chain's packets arrive in bitplane order (its dependencies), so the
  // packet just added is the chain's last; summing the chains in a fixed
  // order makes the estimate independent of the order of arrival.
  if (id < m.estimates.chain.size() && m.estimates.chain[id] < m.chain_now.size()) {
    m.chain_now[m.estimates.chain[id]] = m.estimates.after[id];
  }
  m.distortion = m.estimates.Estimate(m.chain_now);
  return Status::Ok();
}

int ProgressiveDecoder::CompleteLevels() const {
  const Impl& m = *impl_;
  int level = 0;
  for (size_t j = 0; j < m.states.size(); ++j) {
    bool all = true;
    for (const auto& s : m.states[j]) all = all && (s.top < 0 || s.known_from() <= s.top);
    if (!all) break;
    level = static_cast<int>(j) + 1;
  }
  return level;
}

int ProgressiveDecoder::DetailLevels() const {
  const Impl& m = *impl_;
  for (int j = static_cast<int>(m.states.size()) - 1; j >= 0; --j) {
    for (const ComponentState& s : m.states[j]) {
      const int n = s.known_from();
      if (n > s.top) continue;
      // Nonzero exactly as Positions dequantises it.
      for (uint32_t i : s.significant()) {
        if ((s.mag[i] >> n) != 0) return j + 1;
      }
    }
  }
  return 0;
}

double ProgressiveDecoder::EstimatedPsnr() const {
  return EstimatedPsnrFromDistortion(impl_->header, impl_->diagonal, impl_->distortion);
}

std::vector<Vec3> ProgressiveDecoder::Positions(int max_level) const {
  const Impl& m = *impl_;
  const auto& h = *m.hierarchy;
  Pyramid p;
  p.hierarchy = m.hierarchy;
  p.base = m.base.positions;
  p.subbands.resize(h.levels());
  for (int j = 0; j < h.levels(); ++j) {
    if (max_level >= 0 && j >= max_level) break;
    auto& band = p.subbands[j];
    band.assign(h.subband_size(j), Vec3::Zero());
    const CoefficientOctree& tree = m.layouts[j].tree;
    for (int c = 0; c < 3; ++c) {
      const ComponentState& s = m.states[j][c];
      const StreamHeader::Quantizer& q = m.header.quantizer(j, c);
      const int n = s.known_from();
      if (n > s.top) continue;
      const double xi0 = DeadzoneXi(static_cast<int>(q.deadzone));
      // Dequantize(s.mag[i] >> n, n, s.negative[i], q.step, xi0, gamma)
      // with its two ldexp calls, the same for every k, taken out of the
      // loop (the same operations in the same order: bit-identical).
      const double scale = std::ldexp(q.step, n);
      const double xi_n = std::ldexp(xi0, -n);
      const double gamma = m.options.gamma;
      for (uint32_t i : s.significant()) {
        const uint32_t v = s.mag[i] >> n;
        if (v == 0) continue;  // band is zero already
        const double r = (static_cast<double>(v) + gamma - xi_n) * scale;
        band[tree.At(i)][c] = s.negative[i] ? -r : r;
      }
    }
  }
  return m.transform->Inverse(p, max_level);
}

std::vector<Face> ProgressiveDecoder::Faces(int max_level) const {
  const auto& h = *impl_->hierarchy;
  return h.faces((max_level < 0 || max_level > h.levels()) ? h.levels() : max_level);
}

TriMesh ProgressiveDecoder::Mesh(int max_level) const {
  const auto& h = *impl_->hierarchy;
  const int level = (max_level < 0 || max_level > h.levels()) ? h.levels() : max_level;
  TriMesh mesh;
  mesh.positions = Positions(level);
  mesh.faces = Faces(level);
  return mesh;
}

}  // namespace meshwave
