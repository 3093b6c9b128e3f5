#include "meshwave/progressive_decoder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "bitplane/decoder_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "core/deferred.h"
#include "core/parallel_for.h"
#include "core/work_ahead.h"
#include "meshwave/progression.h"
#include "meshwave/semiregular.h"
#include "meshwave/wavelet.h"
#include "attributes/ycocg.h"
#include "quant/deadzone_quantizer.h"
#include "stream/base_mesh_decoder.h"
#include "stream/channel_base_decoder.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "meshwave/packet_parts.h"
#include "stream/original_layer_decoder.h"
#include "stream/precinct_partition.h"
#include "stream/sawt_field_decoder.h"
#include "stream/stream_format.h"
#include "texture/atlas_coordinates.h"
#include "texture/atlas_layout.h"

namespace meshwave {
namespace {

bool SetUpInBackground(int requested) { return ResolveThreads(requested) >= 2; }

// The texture as a validated header describes it.
TextureInfo TextureInfoOf(const StreamHeader::Texture& t) {
  TextureInfo out;
  out.atlas = {t.cell, t.gutter, t.columns};
  TextureMaterial& material = out.material;
  material.metallic_factor = t.metallic_factor;
  material.roughness_factor = t.roughness_factor;
  material.emissive_factor = {t.emissive_factor[0], t.emissive_factor[1], t.emissive_factor[2]};
  material.normal_scale = t.normal_scale;
  material.occlusion_strength = t.occlusion_strength;
  material.alpha_blend = t.alpha_blend;
  material.double_sided = t.double_sided;
  for (const StreamHeader::Texture::Map& map : t.maps) {
    TextureMapInfo& info = out.maps.emplace_back();
    info.role = static_cast<TextureRole>(map.role);
    info.mime_type = map.mime_type;
    for (const StreamHeader::Texture::Level& level : map.levels) {
      info.levels.push_back({level.width, level.height});
    }
  }
  return out;
}

using SignalStates = std::array<ComponentState, 3>;

// Decodes bitplane b of one precinct's three components from `io` with
// `contexts`: the geometry's and a channel's precincts alike. `parent`: the
// parent precinct's states in the subband above (3xC, j > 0), else null.
void DecodePrecinctComponents(const SubbandLayout& layout, SignalStates& states,
                              const SignalStates* parent, bool parent_contexts, int b,
                              ComponentContexts& contexts, DecoderIo& io) {
  for (int c = 0; c < 3; ++c) {
    ComponentState& s = states[c];
    if (b > s.top) continue;
    ContextSources sources;
    if (parent != nullptr) {
      const ComponentState& up = (*parent)[c];
      sources = {layout.parent_position, up.mag, up.negative, {}};
    }
    // 3xC: the neighbour contexts too.
    if (parent_contexts) sources.neighbour_position = layout.neighbour_position;
    CodeBitplane(layout.tree, s, b, sources, contexts, io);
  }
}

// Writes subband j's coefficients as far as decoded into `band` (zero
// where nothing is known): the geometry's and a channel's alike.
void DequantizeSubband(const std::vector<SubbandLayout>& precincts,
                       const std::vector<SignalStates>& states,
                       const std::vector<StreamHeader::Quantizer>& quantizers, int j, double gamma,
                       Vec3* band) {
  for (size_t p = 0; p < precincts.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t* coefficient = precincts[p].coefficient.data();
      const ComponentState& s = states[p][c];
      const StreamHeader::Quantizer& q = quantizers[3 * static_cast<size_t>(j) + c];
      const int n = s.known_from();
      if (n > s.top) continue;
      const double xi0 = DeadzoneXi(static_cast<int>(q.deadzone));
      // Dequantize(s.mag[i] >> n, n, s.negative[i], q.step, xi0, gamma)
      // with its two ldexp calls, the same for every k, taken out of the
      // loop (the same operations in the same order: bit-identical).
      const double scale = std::ldexp(q.step, n);
      const double xi_n = std::ldexp(xi0, -n);
      for (uint32_t i : s.significant()) {
        const uint32_t v = s.mag[i] >> n;
        if (v == 0) continue;  // band is zero already
        const double r = (static_cast<double>(v) + gamma - xi_n) * scale;
        band[coefficient[i]][c] = s.negative[i] ? -r : r;
      }
    }
  }
}

}  // namespace

struct ProgressiveDecoder::Impl {
  // What the packets of subband j decode into: per precinct, its octree
  // and the coding state of its three components.
  struct SubbandCoding {
    std::vector<SubbandLayout> precincts;
    std::vector<std::array<ComponentState, 3>> states;
    // Each precinct's contexts after its share of the last bitplane
    // decoded: where its next part's contexts start (FORMAT.md 5.3).
    std::vector<ComponentContexts> carried;
  };

  // A channel (FORMAT.md 2.3): its base values and, per subband, per
  // precinct of the geometry's layouts, its components' coding state
  // (built when the channel's first packet of the subband or a finer one
  // comes). Its packets are never split: no carried contexts.
  struct ChannelDecoding {
    std::vector<Vec3> base;
    std::vector<std::vector<SignalStates>> states;  // empty until built
    std::vector<char> touched;
  };

  static void InitStates(const StreamHeader& header, int j, SubbandCoding& s) {
    s.states.resize(s.precincts.size());
    s.carried.assign(s.precincts.size(), ComponentContexts{});
    for (size_t p = 0; p < s.precincts.size(); ++p) {
      for (int c = 0; c < 3; ++c) {  // Init reuses the lists' memory
        s.states[p][c].Init(s.precincts[p].tree, header.quantizer(j, c).top_bitplane);
      }
    }
  }

  StreamHeader header;
  DecoderOptions options;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  TransformSettings settings;
  // Each level's stencils built on first use (level 0's by Create).
  std::unique_ptr<WaveletTransform> transform;
  DecodedBase base;
  // The units held, and the rules of what each needs first.
  std::optional<HeldUnits> held;
  // Payload bytes held of split packets partly held.
  std::vector<uint64_t> part_bytes;
  std::vector<std::vector<uint32_t>> chain_packets;  // per chain, in order
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
  std::vector<ChannelDecoding> channels;
  // The channels' inverse transform: the geometry's without local frames
  // (null when the geometry has none: `transform` serves).
  std::unique_ptr<WaveletTransform> channel_transform;
  // The texture (FORMAT.md 2.4): its description, its atlas, and the bytes
  // of each texture packet held (empty when not), from first_texture on.
  TextureInfo texture;
  std::optional<AtlasLayout> atlas;
  uint32_t first_texture = 0;
  std::vector<std::string> texture_bytes;
  // The original layer (FORMAT.md 2.5), when the stream has one (its
  // chain's estimate replaces the remesh's once its mesh is given).
  std::optional<original::LayerDecoder> original;
  // Last, so that it stops (its thread joined) before what it builds goes.
  WorkAhead ahead;

  bool parent_contexts() const { return header.coder == StreamCoder::k3xC; }

  // Whether a packet or part of packet `id` may be offered at all: the
  // decoder not broken, the id in the index.
  Status CheckUsable(uint32_t id) const {
    if (broken) {
      return Status(StatusCode::kInvalidArgument,
                    "decoder is unusable after an earlier corrupt packet");
    }
    if (id >= held->packet_count()) {
      return InvalidArgument("packet " + std::to_string(id) + " is not in the index of " +
                             std::to_string(held->packet_count()) + " packets");
    }
    return Status::Ok();
  }

  // Payload bytes of packet `id` decoded (whole, or some of its parts):
  // its chain's estimate moves. A chain's whole packets arrive in bitplane
  // order (its dependencies); a part counts for its share of the packet's
  // bytes. Summing the chains in a fixed order makes the estimate
  // independent of the order of arrival.
  static void Record(Impl& m, StreamUnit unit, size_t bytes) {
    const uint32_t id = unit.id;
    m.held->Add(unit);
    if (m.held->Has({id})) {
      ++m.decoded;
      m.part_bytes[id] = 0;
    } else {
      m.part_bytes[id] += bytes;
    }
    m.bytes += bytes;
    if (id < m.estimates.chain.size() && m.estimates.chain[id] < m.chain_now.size()) {
      const uint32_t chain = m.estimates.chain[id];
      double term = m.estimates.chain_start[chain];
      for (uint32_t q : m.chain_packets[chain]) {
        if (m.held->Has({q})) {
          term = m.estimates.after[q];
        } else if (m.part_bytes[q] > 0 && m.header.packets.length[q] > 0) {
          term -= m.estimates.reduction[q] * static_cast<double>(m.part_bytes[q]) /
                  static_cast<double>(m.header.packets.length[q]);
        }
      }
      m.chain_now[chain] = term;
    }
    m.distortion = m.estimates.Estimate(m.chain_now);
  }

  // Decodes precinct p's share of bitplane b of subband j from `io` with
  // `contexts`.
  void DecodePrecinct(int j, uint32_t p, int b, ComponentContexts& contexts, DecoderIo& io) {
    SubbandCoding& subband = coding.Get(static_cast<size_t>(j));
    const SubbandLayout& layout = subband.precincts[p];
    // Built before subband j (the sequence's order): no wait, one lock.
    const SubbandCoding* up_coding =
        parent_contexts() && j > 0 ? &coding.Get(static_cast<size_t>(j) - 1) : nullptr;
    DecodePrecinctComponents(layout, subband.states[p],
                             up_coding ? &up_coding->states[layout.parent_precinct] : nullptr,
                             parent_contexts(), b, contexts, io);
  }

  // Channel k's coding state of subbands 0 ... j, built where missing.
  void EnsureChannelStates(size_t k, int j) {
    ChannelDecoding& channel = channels[k];
    for (int jj = 0; jj <= j; ++jj) {
      auto& states = channel.states[static_cast<size_t>(jj)];
      if (!states.empty()) continue;
      const SubbandCoding& subband = coding.Get(static_cast<size_t>(jj));
      states.resize(subband.precincts.size());
      InitChannelStates(k, jj, subband, states);
    }
  }
  void InitChannelStates(size_t k, int j, const SubbandCoding& subband,
                         std::vector<SignalStates>& states) const {
    for (size_t p = 0; p < states.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        states[p][c].Init(subband.precincts[p].tree,
                          header.channels[k].quantizer(j, c).top_bitplane);
      }
    }
  }

  // Decodes channel packet (j, b) of channel k, one codeword over the
  // precincts.
  Status DecodeChannelPacket(size_t k, int j, int b, std::string_view payload) {
    EnsureChannelStates(k, j);
    ChannelDecoding& channel = channels[k];
    channel.touched[static_cast<size_t>(j)] = 1;
    const std::vector<SubbandLayout>& precincts = coding.Get(static_cast<size_t>(j)).precincts;
    DecoderIo io(payload);
    ComponentContexts contexts;
    for (size_t p = 0; p < precincts.size(); ++p) {
      const SignalStates* parent =
          parent_contexts() && j > 0
              ? &channel.states[static_cast<size_t>(j) - 1][precincts[p].parent_precinct]
              : nullptr;
      DecodePrecinctComponents(precincts[p], channel.states[static_cast<size_t>(j)][p], parent,
                               parent_contexts(), b, contexts, io);
    }
    if (io.decoder().overrun()) {
      broken = true;
      return ParseError("payload ends before its symbols (corrupt stream)");
    }
    return Status::Ok();
  }
  // One codeword holding precinct `p`'s share alone (a split packet's part).
  Status DecodePart(int j, uint32_t p, int b, std::string_view part) {
    DecoderIo io(part);
    ComponentContexts& contexts = coding.Get(static_cast<size_t>(j)).carried[p];
    DecodePrecinct(j, p, b, contexts, io);
    if (io.decoder().overrun()) {
      broken = true;
      return ParseError("part " + std::to_string(p) + ": payload ends before its symbols (corrupt stream)");
    }
    return Status::Ok();
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
  // Without a texture, its (empty) range ends where the original layer
  // starts.
  impl->first_texture = static_cast<uint32_t>(impl->packets->original_first());
  if (header.texture) {
    const StreamHeader::Texture& t = *header.texture;
    MW_ASSIGN_OR_RETURN(AtlasLayout atlas,
                        AtlasLayout::Create(header.base.face_count, t.cell, t.gutter, t.columns));
    impl->atlas = atlas;
    impl->texture = TextureInfoOf(t);
    impl->first_texture = static_cast<uint32_t>(impl->packets->TextureId(0, 0));
  }
  if (header.original) {
    // Its vertices too: the layer's decoder holds some 40 bytes for each.
    const uint64_t elements =
        std::max<uint64_t>(header.original->face_count, header.original->vertex_count);
    if (elements > options.max_faces) {
      return Status(StatusCode::kUnsupported,
                    "header: the original layer's " +
                        std::to_string(header.original->vertex_count) + " vertices and " +
                        std::to_string(header.original->face_count) +
                        " faces, more than this decoder's limit of " +
                        std::to_string(options.max_faces));
    }
    impl->original.emplace(*header.original);
  }
  impl->estimates = ReadDistortionIndex(header, PacketChains(header));
  for (const StreamHeader::Channel& channel : header.channels) {
    MW_ASSIGN_OR_RETURN(std::vector<Vec3> base,
                        DecodeChannelBase(channel, impl->hierarchy->vertex_count(0)));
    Impl::ChannelDecoding& decoding = impl->channels.emplace_back();
    decoding.base = std::move(base);
    decoding.states.resize(static_cast<size_t>(impl->hierarchy->levels()));
    decoding.touched.assign(static_cast<size_t>(impl->hierarchy->levels()), 0);
  }
  if (!impl->channels.empty() && impl->settings.frames == FrameMode::kLocal) {
    TransformSettings global = impl->settings;
    global.frames = FrameMode::kGlobal;
    MW_ASSIGN_OR_RETURN(WaveletTransform channel_transform,
                        WaveletTransform::Create(impl->hierarchy, global,
                                                 WaveletTransform::Stencils::kOnFirstUse));
    impl->channel_transform = std::make_unique<WaveletTransform>(std::move(channel_transform));
  }
  // The octrees (about a quarter of the set-up on igea) and the finer
  // levels' stencils (about two thirds) are built on first use, the
  // octrees one subband at a time, coarsest first (a packet waits only for
  // its own subband's), the stencils level by level (a mesh waits only for
  // its levels'). With a second core one thread builds them ahead of use;
  // whatever a caller needs first it builds itself, so the two share the
  // work, and what nobody needed is abandoned when the decoder goes.
  Impl* m = impl.get();
  const PrecinctPartition partition = PartitionIntoPrecincts(
      *m->hierarchy, m->base.grid, m->header.packets.precinct_coefficients);
  // Per subband, each precinct's parent (subband 0's: 0): also their count.
  PrecinctParents parents = partition.ParentsPerSubband();
  if (partition.levels() > 0) parents[0].assign(partition.count(0), 0);
  m->chain_packets.assign(m->estimates.chain_start.size(), {});
  for (uint32_t id = 0; id < m->estimates.chain.size(); ++id) {
    if (m->estimates.chain[id] < m->chain_packets.size()) {
      m->chain_packets[m->estimates.chain[id]].push_back(id);
    }
  }
  auto layouts = std::make_shared<SubbandLayoutBuilder>(
      *m->hierarchy, m->base.grid, m->header.octree_leaf_size,
      partition.FacePrecinctsPerSubband(), parents);
  m->held.emplace(m->header, std::move(parents));
  m->coding.Start(static_cast<size_t>(m->hierarchy->levels()),
                  [m, layouts](size_t j) {
                    Impl::SubbandCoding s{layouts->Next(), {}, {}};
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
  for (size_t k = 0; k < m.channels.size(); ++k) {
    Impl::ChannelDecoding& channel = m.channels[k];
    for (size_t j = 0; j < channel.touched.size(); ++j) {
      if (!channel.touched[j]) continue;
      m.InitChannelStates(k, static_cast<int>(j), m.coding.Get(j), channel.states[j]);
      channel.touched[j] = 0;
    }
  }
  m.held->Clear();
  m.texture_bytes.assign(static_cast<size_t>(m.packets->original_first()) - m.first_texture,
                         std::string());
  if (m.original) m.original->Reset();
  m.part_bytes.assign(m.held->packet_count(), 0);
  m.chain_now = m.estimates.chain_start;
  m.distortion = m.estimates.start();
  m.decoded = 0;
  m.bytes = 0;
  m.broken = false;
}

const StreamHeader& ProgressiveDecoder::header() const { return impl_->header; }
size_t ProgressiveDecoder::packet_count() const { return impl_->held->packet_count(); }
bool ProgressiveDecoder::HasPacket(uint32_t id) const { return impl_->held->Has({id}); }
const HeldUnits& ProgressiveDecoder::held() const { return *impl_->held; }
size_t ProgressiveDecoder::packets_decoded() const { return impl_->decoded; }
uint64_t ProgressiveDecoder::payload_bytes_decoded() const { return impl_->bytes; }

bool ProgressiveDecoder::DependenciesMet(uint32_t id) const {
  return impl_->held->DependenciesMet({id});
}

Status ProgressiveDecoder::AddPacket(uint32_t id, std::string_view payload) {
  Impl& m = *impl_;
  MW_RETURN_IF_ERROR(m.CheckUsable(id));
  const auto& index = m.header.packets;
  const bool base = m.packets->IsBase(id);
  const int j = m.packets->Subband(id);
  const int b = m.packets->Bitplane(id);
  // A packet's name, for errors only: built on the way out (it was a
  // tenth of a small packet's decoding time).
  auto name = [&](uint32_t p) {
    if (const int part = m.packets->OriginalPart(p); part >= 0) {
      return "packet " + std::to_string(p) + " (original layer, " +
             (part == 0 ? std::string("connectivity") : "positions " + std::to_string(part - 1)) +
             ")";
    }
    if (m.packets->IsTexture(p)) {
      return "packet " + std::to_string(p) + " (texture map " +
             std::to_string(m.packets->TextureMap(p)) + ", level " +
             std::to_string(m.packets->Bitplane(p)) + ")";
    }
    if (m.packets->IsBase(p)) {
      return "packet " + std::to_string(p) + " (base refinement, plane " +
             std::to_string(m.packets->Bitplane(p)) + ")";
    }
    return "packet " + std::to_string(p) + " (" +
           (m.packets->IsChannel(p) ? "channel " + std::to_string(m.packets->Channel(p)) + ", "
                                    : std::string()) +
           "subband " + std::to_string(m.packets->Subband(p)) + ", bitplane " +
           std::to_string(m.packets->Bitplane(p)) + ")";
  };
  auto what = [&] { return name(id); };
  if (m.held->Has({id})) return InvalidArgument(what() + " was already added");
  if (int64_t missing = m.held->FirstMissing({id}); missing >= 0) {
    return InvalidArgument(what() + " needs " + name(static_cast<uint32_t>(missing)) + " first");
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
    Impl::Record(m, {id}, payload.size());
    return Status::Ok();
  }
  if (const int part = m.packets->OriginalPart(id); part >= 0) {
    if (Status s = m.original->Add(part, payload); !s.ok()) {
      m.broken = true;
      return s.WithContext(what());
    }
    Impl::Record(m, {id}, payload.size());
    return Status::Ok();
  }
  if (m.packets->IsTexture(id)) {
    // A whole encoded image, kept as it came: whoever shows it decodes it.
    m.texture_bytes[id - m.first_texture].assign(payload);
    Impl::Record(m, {id}, payload.size());
    return Status::Ok();
  }
  if (const int k = m.packets->Channel(id); k >= 0) {
    if (Status s = m.DecodeChannelPacket(static_cast<size_t>(k), j, b, payload); !s.ok()) {
      return s.WithContext(what());
    }
    Impl::Record(m, {id}, payload.size());
    return Status::Ok();
  }
  const auto precincts = static_cast<uint32_t>(m.coding.Get(static_cast<size_t>(j)).precincts.size());
  if (m.packets->IsSplit(id)) {
    auto split = SplitPacketParts(payload, precincts);
    if (!split.ok()) return split.status().WithContext(what());
    const std::vector<std::string_view>& parts = *split;
    m.touched[j] = 1;  // before decoding: a corrupt packet leaves its state changed
    for (uint32_t p = 0; p < precincts; ++p) {
      if (m.held->Has({id, p})) continue;  // sent alone before
      if (Status s = m.DecodePart(j, p, b, parts[p]); !s.ok()) return s.WithContext(what());
    }
  } else {
    m.touched[j] = 1;
    DecoderIo io(payload);
    ComponentContexts contexts;  // shared by the packet's precincts and components
    for (uint32_t p = 0; p < precincts; ++p) m.DecodePrecinct(j, p, b, contexts, io);
    auto& carried = m.coding.Get(j).carried;
    std::fill(carried.begin(), carried.end(), contexts);
    if (io.decoder().overrun()) {
      m.broken = true;
      return ParseError(what() + ": payload ends before its symbols (corrupt stream)");
    }
  }
  // The bytes of parts held before were counted then.
  Impl::Record(m, {id}, payload.size() - std::min<uint64_t>(m.part_bytes[id], payload.size()));
  return Status::Ok();
}

uint32_t ProgressiveDecoder::PartCount(uint32_t id) const { return impl_->held->PartCount(id); }

bool ProgressiveDecoder::HasPart(uint32_t id, uint32_t part) const {
  return part < PartCount(id) && impl_->held->Has({id, part});
}

bool ProgressiveDecoder::PartDependenciesMet(uint32_t id, uint32_t part) const {
  return part < PartCount(id) && impl_->held->DependenciesMet({id, part});
}

Status ProgressiveDecoder::AddPacketPart(uint32_t id, uint32_t part, std::string_view payload) {
  Impl& m = *impl_;
  MW_RETURN_IF_ERROR(m.CheckUsable(id));
  const uint32_t count = m.held->PartCount(id);
  const int j = m.packets->Subband(id);
  const int b = m.packets->Bitplane(id);
  auto name = [&](uint32_t q) {
    return "packet " + std::to_string(q) + " (subband " + std::to_string(m.packets->Subband(q)) +
           ", bitplane " + std::to_string(m.packets->Bitplane(q)) + ")";
  };
  if (count == 0) return InvalidArgument(name(id) + " is not split into precinct parts");
  const std::string what = "part " + std::to_string(part) + " of " + name(id);
  if (part >= count) {
    return InvalidArgument(what + ": the packet has " + std::to_string(count) + " parts");
  }
  if (m.held->Has({id, part})) return InvalidArgument(what + " was already added");
  if (int64_t missing = m.held->FirstMissing({id, part}); missing >= 0) {
    return InvalidArgument(what + " needs its share of " + name(static_cast<uint32_t>(missing)) +
                           " first");
  }
  if (payload.size() > m.header.packets.length[id]) {
    return ParseError(what + ": " + std::to_string(payload.size()) +
                      " bytes, more than the whole packet's " +
                      std::to_string(m.header.packets.length[id]));
  }
  m.touched[j] = 1;
  if (Status s = m.DecodePart(j, part, b, payload); !s.ok()) return s.WithContext(name(id));
  Impl::Record(m, {id, part}, payload.size());
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
        for (const auto& states : m.coding.Get(j).states) {
          const ComponentState& s = states[c];
          all = all && (s.top < 0 || s.known_from() <= s.top);
        }
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
    for (const auto& states : m.coding.Get(j).states) {
      for (const ComponentState& s : states) {
        const int n = s.known_from();
        if (n > s.top) continue;
        // Nonzero exactly as Positions dequantises it.
        for (uint32_t i : s.significant()) {
          if ((s.mag[i] >> n) != 0) return j + 1;
        }
      }
    }
  }
  return 0;
}

double ProgressiveDecoder::EstimatedPsnr() const {
  const Impl& m = *impl_;
  return EstimatedPsnrFromDistortion(m.header, m.diagonal,
                                     OriginalReady() ? m.estimates.ShownEstimate(m.chain_now, true)
                                                     : m.distortion);
}

bool ProgressiveDecoder::HasOriginal() const { return impl_->original.has_value(); }

bool ProgressiveDecoder::OriginalReady() const {
  return impl_->original && impl_->original->ready();
}

TriMesh ProgressiveDecoder::OriginalMesh() const {
  return OriginalReady() ? impl_->original->Mesh() : TriMesh();
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
    const Impl::SubbandCoding& coding = m.coding.Get(j);
    DequantizeSubband(coding.precincts, coding.states, m.header.quantizers, j, m.options.gamma,
                      x.data() + h.vertex_count(j));
  }
  m.transform->InverseInPlace(x, level);
  return x;
}

bool ProgressiveDecoder::HasColors() const {
  for (const StreamHeader::Channel& channel : impl_->header.channels) {
    if (channel.kind == StreamChannelKind::kColor) return true;
  }
  return false;
}

std::vector<Vec3> ProgressiveDecoder::Colors(int max_level) const {
  const Impl& m = *impl_;
  size_t k = 0;
  while (k < m.header.channels.size() && m.header.channels[k].kind != StreamChannelKind::kColor) {
    ++k;
  }
  if (k == m.header.channels.size()) return {};
  const auto& h = *m.hierarchy;
  const int level = (max_level < 0 || max_level > h.levels()) ? h.levels() : max_level;
  const Impl::ChannelDecoding& channel = m.channels[k];
  // As Positions: the base values, each subband's details in place, the
  // inverse transform (without local frames), then back to RGB.
  std::vector<Vec3> x(h.vertex_count(level), Vec3::Zero());
  std::copy(channel.base.begin(), channel.base.end(), x.begin());
  for (int j = 0; j < level; ++j) {
    if (!channel.touched[static_cast<size_t>(j)]) continue;
    DequantizeSubband(m.coding.Get(j).precincts, channel.states[static_cast<size_t>(j)],
                      m.header.channels[k].quantizers, j, m.options.gamma,
                      x.data() + h.vertex_count(j));
  }
  const WaveletTransform& transform = m.channel_transform ? *m.channel_transform : *m.transform;
  transform.InverseInPlace(x, level);
  for (Vec3& v : x) v = YCoCgToRgb(v).cwiseMax(0.0).cwiseMin(1.0);
  return x;
}

bool ProgressiveDecoder::HasTexture() const { return impl_->atlas.has_value(); }

const TextureInfo& ProgressiveDecoder::texture() const { return impl_->texture; }

std::vector<float> ProgressiveDecoder::TextureCoordinates(int max_level) const {
  const Impl& m = *impl_;
  if (!m.atlas) return {};
  const int levels = m.hierarchy->levels();
  const int level = (max_level < 0 || max_level > levels) ? levels : max_level;
  return AtlasCoordinates(*m.atlas, m.header.texture->face_triangles, level);
}

std::optional<TextureImage> ProgressiveDecoder::BestTextureLevel(size_t map) const {
  const Impl& m = *impl_;
  if (map >= m.texture.maps.size()) return std::nullopt;
  const TextureMapInfo& info = m.texture.maps[map];
  for (int k = static_cast<int>(info.levels.size()) - 1; k >= 0; --k) {
    const auto id = static_cast<uint32_t>(m.packets->TextureId(static_cast<int>(map), k));
    if (!m.held->Has({id})) continue;
    TextureImage image;
    image.role = info.role;
    image.mime_type = info.mime_type;
    image.level = k;
    image.width = info.levels[static_cast<size_t>(k)].width;
    image.height = info.levels[static_cast<size_t>(k)].height;
    image.bytes = m.texture_bytes[id - m.first_texture];
    return image;
  }
  return std::nullopt;
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
