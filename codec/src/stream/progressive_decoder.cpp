#include "meshwave/progressive_decoder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "bitplane/bitplane_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "core/deferred.h"
#include "core/parallel_for.h"
#include "core/work_ahead.h"
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
namespace {

bool SetUpInBackground(int requested) { return ResolveThreads(requested) >= 2; }

}  // namespace

struct ProgressiveDecoder::Impl {
  // What the packets of subband j decode into: its octree and the coding
  // state of its three components.
  struct SubbandCoding {
    SubbandLayout layout;
    std::array<ComponentState, 3> states;
  };

  static void InitStates(const StreamHeader& header, int j, SubbandCoding& s) {
    for (int c = 0; c < 3; ++c) {  // Init reuses the lists' memory
      s.states[c].Init(s.layout.tree, header.quantizer(j, c).top_bitplane);
    }
  }

  StreamHeader header;
  DecoderOptions options;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  TransformSettings settings;
  // Each level's stencils built on first use (level 0's by Create).
  std::unique_ptr<WaveletTransform> transform;
  DecodedBase base;
  std::vector<char> have;
  // Subbands a packet has decoded into since the last Reset: the others
  // hold their initial state, which nobody needs to wait for.
  std::vector<char> touched;
  std::unique_ptr<PacketLayout> packets;
  DistortionEstimates estimates;
  std::vector<double> chain_now;  // each chain's estimated term now
  size_t decoded = 0;
  uint64_t bytes = 0;
  double distortion = 0;
  bool broken = false;
  double diagonal = 0;
  DeferredSequence<SubbandCoding> coding;  // subband by subband, coarsest first
  // Last, so that it stops (its thread joined) before what it builds goes.
  WorkAhead ahead;

  bool parent_contexts() const { return header.coder == StreamCoder::k3xC; }

  // Packet `id` decoded: it is held, and its chain's estimate moves.
  static void Record(Impl& m, uint32_t id, size_t bytes) {
    m.have[id] = 1;
    ++m.decoded;
    m.bytes += bytes;
    // A chain's packets arrive in bitplane order (its dependencies), so the
    // packet just added is the chain's last; summing the chains in a fixed
    // order makes the estimate independent of the order of arrival.
    if (id < m.estimates.chain.size() && m.estimates.chain[id] < m.chain_now.size()) {
      m.chain_now[m.estimates.chain[id]] = m.estimates.after[id];
    }
    m.distortion = m.estimates.Estimate(m.chain_now);
  }
  // No packet has touched the coding state: every detail is zero, and no
  // caller needs to wait for that state to be built.
  bool fresh() const { return decoded == 0 && !broken; }

  // The set-up ahead of use, in the order a stream in any packet order
  // needs it: subband j's octree for its packets, then level j + 1's
  // stencils for the mesh one level past them (level 0's are built).
  void WorkAheadStep(size_t step) const {
    const size_t j = step / 2;
    if (step % 2 == 0) {
      coding.Get(j);
    } else if (static_cast<int>(j) + 1 < transform->levels()) {
      transform->PrepareLevel(static_cast<int>(j) + 1);
    }
  }
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
  MW_ASSIGN_OR_RETURN(impl->settings,
                      SetUpHierarchy(header, options.max_base_vertices, impl->base,
                                     impl->hierarchy));
  impl->diagonal = HeaderDiagonal(header);
  // Level 0's vertex rings are checked here: the finer levels subdivide it.
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(impl->hierarchy, impl->settings,
                                               WaveletTransform::Stencils::kOnFirstUse));
  impl->transform = std::make_unique<WaveletTransform>(std::move(transform));
  impl->packets = std::make_unique<PacketLayout>(header);
  impl->estimates = ReadDistortionIndex(header, PacketChains(header));
  // The octrees (about a quarter of the set-up on igea) and the finer
  // levels' stencils (about two thirds) are built on first use, the
  // octrees one subband at a time, coarsest first (a packet waits only for
  // its own subband's), the stencils level by level (a mesh waits only for
  // its levels'). With a second core one thread builds them ahead of use;
  // whatever a caller needs first it builds itself, so the two share the
  // work, and what nobody needed is abandoned when the decoder goes.
  Impl* m = impl.get();
  auto layouts = std::make_shared<SubbandLayoutBuilder>(*m->hierarchy, m->base.grid,
                                                        m->header.octree_leaf_size);
  m->coding.Start(static_cast<size_t>(m->hierarchy->levels()),
                  [m, layouts](size_t j) {
                    Impl::SubbandCoding s{layouts->Next(), {}};
                    Impl::InitStates(m->header, static_cast<int>(j), s);
                    return s;
                  });
  if (SetUpInBackground(options.threads)) {
    m->ahead.Start(2 * m->coding.size(), [m](size_t step) { m->WorkAheadStep(step); });
  }
  std::unique_ptr<ProgressiveDecoder> decoder(new ProgressiveDecoder(std::move(impl)));
  decoder->Reset();
  return decoder;
}

void ProgressiveDecoder::CompleteSetUp() const {
  for (size_t j = 0; j < impl_->coding.size(); ++j) {
    impl_->coding.Get(j);
    impl_->transform->PrepareLevel(static_cast<int>(j));
  }
}

void ProgressiveDecoder::Reset() {
  Impl& m = *impl_;
  // Only decoding changes the coding state (a packet refused before it
  // decodes changes nothing): fresh states need no new start, nor waiting.
  if (!m.fresh()) {
    for (size_t j = 0; j < m.touched.size(); ++j) {
      if (m.touched[j]) Impl::InitStates(m.header, static_cast<int>(j), m.coding.Get(j));
    }
  }
  // A base refinement packet moved the base: back to the header's.
  if (m.base.missing_planes != static_cast<int>(m.header.base.refinement_planes)) {
    ForgetBaseRefinement(m.header.base, m.base);
  }
  m.touched.assign(m.coding.size(), 0);
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
  const bool base = m.packets->IsBase(id);
  const int j = m.packets->Subband(id);
  const int b = m.packets->Bitplane(id);
  // A packet's name, for errors only: built on the way out (it was a
  // tenth of a small packet's decoding time).
  auto name = [&](uint32_t p) {
    if (m.packets->IsBase(p)) {
      return "packet " + std::to_string(p) + " (base refinement, plane " +
             std::to_string(m.packets->Bitplane(p)) + ")";
    }
    return "packet " + std::to_string(p) + " (subband " + std::to_string(m.packets->Subband(p)) +
           ", bitplane " + std::to_string(m.packets->Bitplane(p)) + ")";
  };
  auto what = [&] { return name(id); };
  if (m.have[id]) return InvalidArgument(what() + " was already added");
  for (uint32_t d : m.packets->Dependencies(id, m.parent_contexts())) {
    if (!m.have[d]) return InvalidArgument(what() + " needs " + name(d) + " first");
  }
  if (payload.size() != index.length[id]) {
    return ParseError(what() + ": " + std::to_string(payload.size()) + " bytes, index says " +
                      std::to_string(index.length[id]));
  }
  if (!PacketCheckMatches(index, id, payload)) {
    return ParseError(what() + ": CRC-16 check mismatch (corrupt payload)");
  }
  if (base) {
    // Its length is checked (the index's, validated): every bit pattern is
    // a refinement, and the dependencies bring the planes in turn.
    if (Status s = RefineBase(m.header.base, b, payload, m.base); !s.ok()) {
      m.broken = true;
      return s.WithContext(what());
    }
    Impl::Record(m, id, payload.size());
    return Status::Ok();
  }
  m.touched[j] = 1;  // before decoding: a corrupt packet leaves its state changed
  Impl::SubbandCoding& coding = m.coding.Get(j);
  DecoderIo io(payload);
  const SubbandLayout& layout = coding.layout;
  // Built before subband j (the sequence's order): no wait, one lock.
  const Impl::SubbandCoding* up_coding =
      m.parent_contexts() && j > 0 ? &m.coding.Get(j - 1) : nullptr;
  ComponentContexts contexts;  // shared by the packet's three components
  for (int c = 0; c < 3; ++c) {
    ComponentState& s = coding.states[c];
    if (b > s.top) continue;
    ContextSources sources;
    if (up_coding != nullptr) {
      const ComponentState& up = up_coding->states[c];
      sources = {layout.parent_position, up.mag, up.negative, {}};
    }
    // 3xC: the neighbour contexts too.
    if (m.parent_contexts()) sources.neighbour_position = layout.neighbour_position;
    CodeBitplane(layout.tree, s, b, sources, contexts, io);
  }
  if (io.decoder().overrun()) {
    m.broken = true;
    return ParseError(what() + ": payload ends before its symbols (corrupt stream)");
  }
  Impl::Record(m, id, payload.size());
  return Status::Ok();
}

int ProgressiveDecoder::CompleteLevels() const {
  const Impl& m = *impl_;
  const int levels = m.hierarchy->levels();
  // Every level's positions rest on the base's.
  if (m.base.missing_planes > 0) return 0;
  int level = 0;
  for (int j = 0; j < levels; ++j) {
    bool all = true;
    for (int c = 0; c < 3; ++c) {
      // Before any packet a component is complete only with nothing to code.
      const int top = m.header.quantizer(j, c).top_bitplane;
      if (!m.touched[j]) {
        all = all && top < 0;
      } else {
        const ComponentState& s = m.coding.Get(j).states[c];
        all = all && (s.top < 0 || s.known_from() <= s.top);
      }
    }
    if (!all) break;
    level = j + 1;
  }
  return level;
}

int ProgressiveDecoder::DetailLevels() const {
  const Impl& m = *impl_;
  for (int j = static_cast<int>(m.touched.size()) - 1; j >= 0; --j) {
    if (!m.touched[j]) continue;  // no detail, and no waiting for its state
    for (const ComponentState& s : m.coding.Get(j).states) {
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
  const int level = (max_level < 0 || max_level > h.levels()) ? h.levels() : max_level;
  // The base, then each subband dequantised where its level's new vertices
  // go: the inverse transform works on it in place.
  std::vector<Vec3> x(h.vertex_count(level), Vec3::Zero());
  std::copy(m.base.positions.begin(), m.base.positions.end(), x.begin());
  for (int j = 0; j < level; ++j) {
    if (!m.touched[j]) continue;  // every detail is zero yet
    Vec3* band = x.data() + h.vertex_count(j);
    const Impl::SubbandCoding& coding = m.coding.Get(j);
    const CoefficientOctree& tree = coding.layout.tree;
    for (int c = 0; c < 3; ++c) {
      const ComponentState& s = coding.states[c];
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
  m.transform->InverseInPlace(x, level);
  return x;
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
