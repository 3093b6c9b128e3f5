#include <algorithm>
#include <array>
#include <string>

#include "core/edge_index_table.h"
#include "entropy/adaptive_golomb_encoder.h"
#include "entropy/arithmetic_encoder.h"
#include "original/original_connectivity.h"
#include "original/original_connectivity_code.h"

namespace meshwave::original {
namespace {

constexpr uint32_t kNoFace = 0xffffffffu;

// The faces the traversal can take: distinct corners, and no edge in more
// than two of them (taken in input order; the others go to the fallback
// list). For each taken face's edge, the two faces on it.
struct TraversableFaces {
  std::vector<char> taken;                          // by input face
  EdgeIndexTable edge_slot;                         // edge -> index in faces_on_edge
  std::vector<std::array<uint32_t, 2>> faces_on_edge;

  explicit TraversableFaces(const std::vector<Face>& faces)
      : taken(faces.size(), 0), edge_slot(faces.size() * 3 / 2) {
    faces_on_edge.reserve(faces.size() * 3 / 2 + 3);
    for (uint32_t f = 0; f < faces.size(); ++f) {
      const Face& face = faces[f];
      if (!connectivity::Distinct(face)) continue;
      bool fits = true;
      for (int c = 0; c < 3 && fits; ++c) {
        const uint32_t* slot = edge_slot.Find(face[c], face[(c + 1) % 3]);
        if (slot != nullptr && faces_on_edge[*slot][1] != kNoFace) fits = false;
      }
      if (!fits) continue;
      taken[f] = 1;
      for (int c = 0; c < 3; ++c) {
        const auto [slot, fresh] = edge_slot.Emplace(face[c], face[(c + 1) % 3],
                                                     static_cast<uint32_t>(faces_on_edge.size()));
        if (fresh) {
          faces_on_edge.push_back({f, kNoFace});
        } else {
          faces_on_edge[slot][1] = f;
        }
      }
    }
  }

  // The other traversable face on edge {a, b} of face f, or kNoFace.
  uint32_t Across(uint32_t f, uint32_t a, uint32_t b) const {
    const uint32_t* slot = edge_slot.Find(a, b);
    if (slot == nullptr) return kNoFace;  // not reached: every taken face's edges are in
    const auto& pair = faces_on_edge[*slot];
    return pair[0] == f ? pair[1] : pair[0];
  }
};

class Encoder {
 public:
  Encoder(uint32_t vertex_count, const std::vector<Face>& faces, Traversal* out)
      : vertex_count_(vertex_count),
        faces_(faces),
        traversable_(faces),
        out_(*out),
        position_(vertex_count, kNoVertex),
        region_(vertex_count, faces.size()) {}

  std::string Run() {
    out_.faces.reserve(faces_.size());
    out_.order.reserve(vertex_count_);
    out_.predictions.reserve(vertex_count_);
    // Coded or waiting behind a gate; faces the traversal cannot take
    // count as done here.
    std::vector<char> done(faces_.size());
    for (size_t f = 0; f < faces_.size(); ++f) done[f] = !traversable_.taken[f];
    for (uint32_t start = 0; start < faces_.size(); ++start) {
      if (done[start]) continue;
      done[start] = 1;
      enc_.Encode(1, ctx_.another_component);
      const Face& first = faces_[start];
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = first[c];
        const bool fresh = position_[v] == kNoVertex;
        enc_.Encode(fresh, ctx_.traversal.is_new_first);
        if (fresh) {
          Prediction p;
          if (c >= 1) p.a = first[0];
          if (c == 2) p.b = first[1];
          Introduce(v, p);
        } else {
          CodeOlder(v);
        }
      }
      Finish(start, first, 0, done);
      while (!stack_.empty()) {
        const auto [gate, g] = stack_.back();
        stack_.pop_back();
        const Face& f = faces_[g];
        Face of{};
        bool flipped = false;
        for (int c = 0; c < 3; ++c) {
          const uint32_t u = f[c], w = f[(c + 1) % 3], x = f[(c + 2) % 3];
          if (u == gate.b && w == gate.a) of = {gate.b, gate.a, x};
          if (u == gate.a && w == gate.b) {
            of = {gate.a, gate.b, x};
            flipped = true;
          }
        }
        enc_.Encode(flipped, ctx_.traversal.flipped);
        const uint32_t x = of[2];
        const bool fresh = position_[x] == kNoVertex;
        enc_.Encode(fresh, ctx_.traversal.is_new_third);
        if (fresh) {
          Introduce(x, Prediction{gate.a, gate.b, gate.c});
        } else {
          region_.BorderCandidates(gate.a, gate.b, candidates_);
          const auto it = std::find(candidates_.begin(), candidates_.end(), x);
          enc_.Encode(it != candidates_.end(), ctx_.traversal.on_border);
          if (it != candidates_.end()) {
            const uint32_t i = static_cast<uint32_t>(it - candidates_.begin());
            enc_.Encode(i == 0, FirstBorderContext(ctx_, candidates_.size()));
            if (i > 0) {
              enc_.Encode(i == 1, ctx_.border_second);
              if (i > 1) EncodeGolomb(enc_, ctx_.traversal.border_index, i - 2);
            }
          } else {
            CodeOlder(x);
          }
        }
        Finish(g, of, 1, done);
      }
    }
    enc_.Encode(0, ctx_.another_component);
    CodeFallback();
    return enc_.Finish();
  }

 private:
  void Introduce(uint32_t v, const Prediction& p) {
    const auto& listed = likely_.For(p, vertex_count_, position_);
    const auto it = std::find(listed.begin(), listed.end(), v);
    enc_.Encode(it != listed.end(), ctx_.id_listed);
    if (it != listed.end()) {
      EncodeGolomb(enc_, ctx_.id_list_index, static_cast<uint32_t>(it - listed.begin()));
    } else {
      EncodeSignedGolomb(enc_, ctx_.id_delta, int64_t{v} - likely_.Next());
    }
    likely_.Introduce(v, p, vertex_count_, position_);
    Append(v, p);
  }

  void Append(uint32_t v, const Prediction& p) {
    position_[v] = static_cast<uint32_t>(out_.order.size());
    out_.order.push_back(v);
    out_.predictions.push_back(p);
  }

  void CodeOlder(uint32_t v) {
    EncodeGolomb(enc_, ctx_.traversal.back,
                 static_cast<uint32_t>(out_.order.size()) - 1 - position_[v]);
  }

  // Records face f (rotated as `of`) and opens its gates.
  void Finish(uint32_t f, const Face& of, int first, std::vector<char>& done) {
    const std::array<bool, 3> ask = connectivity::EdgesToAsk(region_, of, first);
    region_.Add(of);  // cannot fail: traversable faces keep edges in two faces
    out_.faces.push_back(of);
    std::array<std::pair<PendingGate, uint32_t>, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (!ask[c]) continue;
      const uint32_t g = traversable_.Across(f, of[c], of[(c + 1) % 3]);
      const bool enters = g != kNoFace && !done[g];
      enc_.Encode(enters, ctx_.traversal.enters[c]);
      if (enters) {
        done[g] = 1;
        opened[n++] = {PendingGate{of[c], of[(c + 1) % 3], of[(c + 2) % 3]}, g};
      }
    }
    // Depth first, lowest slot first, as the base mesh's traversal.
    while (n > 0) stack_.push_back(opened[--n]);
  }

  // The faces the traversal could not take, then the vertices no face
  // introduced.
  void CodeFallback() {
    std::vector<Face> rest;
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!traversable_.taken[f]) rest.push_back(RotateToSmallest(faces_[f]));
    }
    std::sort(rest.begin(), rest.end());
    // The counts the header announces are checked against these two.
    EncodeGolomb(enc_, ctx_.fallback_count, static_cast<uint32_t>(rest.size()));
    uint32_t previous = 0;
    for (const Face& f : rest) {
      EncodeGolomb(enc_, ctx_.fallback_first, f[0] - previous);
      EncodeGolomb(enc_, ctx_.fallback_other, f[1] - f[0]);
      EncodeGolomb(enc_, ctx_.fallback_other, f[2] - f[0]);
      previous = f[0];
      out_.faces.push_back(f);
      for (uint32_t v : f) {
        if (position_[v] == kNoVertex) AppendAfterPrevious(v);
      }
    }
    EncodeGolomb(enc_, ctx_.fallback_count, vertex_count_ - static_cast<uint32_t>(out_.order.size()));
    for (uint32_t v = 0; v < vertex_count_; ++v) {
      if (position_[v] == kNoVertex) AppendAfterPrevious(v);
    }
  }

  void AppendAfterPrevious(uint32_t v) {
    Prediction p;
    if (!out_.order.empty()) p.a = out_.order.back();
    Append(v, p);
  }

  const uint32_t vertex_count_;
  const std::vector<Face>& faces_;
  const TraversableFaces traversable_;
  Traversal& out_;
  std::vector<uint32_t> position_;  // in out_.order, by id
  connectivity::CodedRegion region_;
  ArithmeticEncoder enc_;
  ConnectivityContexts ctx_;
  IdCandidates likely_;
  std::vector<std::pair<PendingGate, uint32_t>> stack_;  // gate, face behind it
  std::vector<uint32_t> candidates_;
};

}  // namespace

Result<std::string> EncodeConnectivity(uint32_t vertex_count, const std::vector<Face>& faces,
                                       Traversal* traversal) {
  if (faces.size() >= kNoVertex) return InvalidArgument("original mesh: over 2^32 - 2 faces");
  for (size_t f = 0; f < faces.size(); ++f) {
    for (uint32_t v : faces[f]) {
      if (v >= vertex_count) {
        return InvalidArgument("original mesh: face " + std::to_string(f) + " names vertex " +
                               std::to_string(v) + " of " + std::to_string(vertex_count));
      }
    }
  }
  Traversal local;
  Traversal& out = traversal != nullptr ? *traversal : local;
  out = Traversal{};
  return Encoder(vertex_count, faces, &out).Run();
}

}  // namespace meshwave::original
