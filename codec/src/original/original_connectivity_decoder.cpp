#include <algorithm>
#include <array>
#include <string>

#include "entropy/adaptive_golomb_decoder.h"
#include "entropy/arithmetic_decoder.h"
#include "original/original_connectivity.h"
#include "original/original_connectivity_code.h"

namespace meshwave::original {
namespace {

// Faces an untrusted count may reserve room for before they decode.
constexpr uint64_t kUntrustedFacesAhead = uint64_t{1} << 16;

class Decoder {
 public:
  Decoder(std::string_view payload, uint32_t vertex_count, uint64_t face_count)
      : dec_(payload),
        vertex_count_(vertex_count),
        face_count_(face_count),
        position_(vertex_count, kNoVertex),
        region_(vertex_count, std::min(face_count, kUntrustedFacesAhead)) {
    out_.faces.reserve(std::min(face_count, kUntrustedFacesAhead));
    out_.order.reserve(vertex_count);
    out_.predictions.reserve(vertex_count);
  }

  Result<Traversal> Run() {
    MW_RETURN_IF_ERROR(DecodeTraversal());
    MW_RETURN_IF_ERROR(DecodeFallback());
    if (dec_.overrun()) return Fail("is cut short: the bytes end");
    return std::move(out_);
  }

 private:
  Status Fail(const std::string& what) const {
    return ParseError("original mesh: face " + std::to_string(out_.faces.size()) + " " + what);
  }

  Status DecodeTraversal() {
    while (dec_.Decode(ctx_.another_component)) {
      if (out_.faces.size() >= face_count_) return Fail("is one more than announced");
      Face first{};
      for (int c = 0; c < 3; ++c) {
        if (dec_.Decode(ctx_.traversal.is_new_first)) {
          Prediction p;
          if (c >= 1) p.a = first[0];
          if (c == 2) p.b = first[1];
          MW_ASSIGN_OR_RETURN(first[c], Introduce(p));
        } else {
          MW_ASSIGN_OR_RETURN(first[c], Older());
        }
      }
      MW_RETURN_IF_ERROR(Finish(first, 0));
      while (!stack_.empty()) {
        if (out_.faces.size() >= face_count_) return Fail("is one more than announced");
        if ((out_.faces.size() & 1023) == 0 && dec_.overrun()) return Fail("is missing: the bytes end");
        const PendingGate gate = stack_.back();
        stack_.pop_back();
        const bool flipped = dec_.Decode(ctx_.traversal.flipped);
        uint32_t x = 0;
        if (dec_.Decode(ctx_.traversal.is_new_third)) {
          MW_ASSIGN_OR_RETURN(x, Introduce(Prediction{gate.a, gate.b, gate.c}));
        } else if (region_.BorderCandidates(gate.a, gate.b, candidates_),
                   dec_.Decode(ctx_.traversal.on_border)) {
          uint32_t i = 0;
          if (!dec_.Decode(FirstBorderContext(ctx_, candidates_.size()))) {
            i = dec_.Decode(ctx_.border_second) ? 1 : 2 + DecodeGolomb(dec_, ctx_.traversal.border_index);
          }
          if (i >= candidates_.size()) return Fail("names a border vertex that does not exist");
          x = candidates_[i];
        } else {
          MW_ASSIGN_OR_RETURN(x, Older());
        }
        MW_RETURN_IF_ERROR(Finish(flipped ? Face{gate.a, gate.b, x} : Face{gate.b, gate.a, x}, 1));
      }
      if ((out_.faces.size() & 1023) == 0 && dec_.overrun()) return Fail("is missing: the bytes end");
    }
    return Status::Ok();
  }

  // A vertex the traversal meets for the first time: its original id.
  Result<uint32_t> Introduce(const Prediction& p) {
    int64_t id;
    const auto& listed = likely_.For(p, vertex_count_, position_);
    if (dec_.Decode(ctx_.id_listed)) {
      const uint32_t i = DecodeGolomb(dec_, ctx_.id_list_index);
      if (i >= listed.size()) return Fail("names a likely vertex id that does not exist");
      id = listed[i];
    } else {
      id = likely_.Next() + DecodeSignedGolomb(dec_, ctx_.id_delta);
    }
    if (id < 0 || id >= vertex_count_) {
      return Fail("names vertex id " + std::to_string(id) + " of " + std::to_string(vertex_count_));
    }
    const uint32_t v = static_cast<uint32_t>(id);
    if (position_[v] != kNoVertex) return Fail("introduces vertex " + std::to_string(v) + " twice");
    likely_.Introduce(v, p, vertex_count_, position_);
    Append(v, p);
    return v;
  }

  // A vertex already in the order, by how far back.
  Result<uint32_t> Older() {
    const uint32_t back = DecodeGolomb(dec_, ctx_.traversal.back);
    if (back >= out_.order.size()) return Fail("names a vertex not seen yet");
    return out_.order[out_.order.size() - 1 - back];
  }

  void Append(uint32_t v, const Prediction& p) {
    position_[v] = static_cast<uint32_t>(out_.order.size());
    out_.order.push_back(v);
    out_.predictions.push_back(p);
  }

  Status Finish(const Face& f, int first) {
    if (!connectivity::Distinct(f)) return Fail("repeats a vertex");
    const std::array<bool, 3> ask = connectivity::EdgesToAsk(region_, f, first);
    if (!region_.Add(f)) return Fail("puts an edge in a third face");
    out_.faces.push_back(f);
    std::array<PendingGate, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (ask[c] && dec_.Decode(ctx_.traversal.enters[c])) {
        opened[n++] = PendingGate{f[c], f[(c + 1) % 3], f[(c + 2) % 3]};
      }
    }
    while (n > 0) stack_.push_back(opened[--n]);
    return Status::Ok();
  }

  Status DecodeFallback() {
    const uint64_t rest = DecodeGolomb(dec_, ctx_.fallback_count);
    if (out_.faces.size() + rest != face_count_) {
      return Fail("starts " + std::to_string(rest) + " faces the traversal left, not the " +
                  std::to_string(face_count_ - out_.faces.size()) + " announced");
    }
    uint64_t previous = 0;
    while (out_.faces.size() < face_count_) {
      if ((out_.faces.size() & 1023) == 0 && dec_.overrun()) return Fail("is missing: the bytes end");
      Face f;
      const uint64_t smallest = previous + DecodeGolomb(dec_, ctx_.fallback_first);
      const uint64_t second = smallest + DecodeGolomb(dec_, ctx_.fallback_other);
      const uint64_t third = smallest + DecodeGolomb(dec_, ctx_.fallback_other);
      if (std::max(second, third) >= vertex_count_) {
        return Fail("names a vertex id past the " + std::to_string(vertex_count_) + " announced");
      }
      f = {static_cast<uint32_t>(smallest), static_cast<uint32_t>(second),
           static_cast<uint32_t>(third)};
      previous = smallest;
      out_.faces.push_back(f);
      for (uint32_t v : f) {
        if (position_[v] == kNoVertex) AppendAfterPrevious(v);
      }
    }
    const uint32_t isolated = DecodeGolomb(dec_, ctx_.fallback_count);
    if (uint64_t{isolated} + out_.order.size() != vertex_count_) {
      return ParseError("original mesh: " + std::to_string(out_.order.size()) + " vertices in faces and " +
                        std::to_string(isolated) + " in none, not the " +
                        std::to_string(vertex_count_) + " announced");
    }
    for (uint32_t v = 0; v < vertex_count_; ++v) {
      if (position_[v] == kNoVertex) AppendAfterPrevious(v);
    }
    return Status::Ok();
  }

  void AppendAfterPrevious(uint32_t v) {
    Prediction p;
    if (!out_.order.empty()) p.a = out_.order.back();
    Append(v, p);
  }

  ArithmeticDecoder dec_;
  const uint32_t vertex_count_;
  const uint64_t face_count_;
  Traversal out_;
  std::vector<uint32_t> position_;  // in out_.order, by id
  connectivity::CodedRegion region_;
  ConnectivityContexts ctx_;
  IdCandidates likely_;
  std::vector<PendingGate> stack_;
  std::vector<uint32_t> candidates_;
};

}  // namespace

Result<Traversal> DecodeConnectivity(std::string_view payload, uint32_t vertex_count,
                                     uint64_t face_count) {
  return Decoder(payload, vertex_count, face_count).Run();
}

}  // namespace meshwave::original
