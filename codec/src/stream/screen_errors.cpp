#include "meshwave/screen_errors.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/semiregular.h"
#include "semiregular/base_face_of.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "stream/precinct_partition.h"
#include "stream/stream_format.h"
#include "mesh/vertex_normals.h"

namespace meshwave {
namespace {

// The base face of every finest vertex: a base vertex's first face, the
// vertex that splits edge k of M^j the base face of coefficient k of d^j.
std::vector<uint32_t> VertexBaseFaces(const SemiRegularHierarchy& h) {
  std::vector<uint32_t> out(h.vertex_count(h.levels()), 0);
  const auto& base = h.faces(0);
  for (uint32_t f = static_cast<uint32_t>(base.size()); f-- > 0;) {
    for (uint32_t v : base[f]) out[v] = f;
  }
  for (int j = 0; j < h.levels(); ++j) {
    const uint32_t first = h.vertex_count(j);
    for (uint32_t k = 0; k < h.subband_size(j); ++k) out[first + k] = BaseFaceOf(h, j, k);
  }
  return out;
}

Status Add(ProgressiveDecoder& d, std::span<const std::string_view> payloads, int id) {
  if (id < 0) return Status::Ok();
  return d.AddPacket(static_cast<uint32_t>(id), payloads[static_cast<size_t>(id)]);
}

}  // namespace

Result<StreamScreenErrors> StreamScreenErrors::Measure(const StreamHeader& header,
                                                       std::span<const std::string_view> payloads,
                                                       const StreamPrecincts& precincts) {
  const PacketLayout layout(header);
  if (payloads.size() != static_cast<size_t>(layout.count())) {
    return InvalidArgument("screen errors: " + std::to_string(payloads.size()) +
                           " payloads for " + std::to_string(layout.count()) + " packets");
  }
  StreamScreenErrors out;
  const int levels = std::min(layout.levels(), precincts.levels());
  if (levels == 0) return out;
  DecodedBase base;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  MW_RETURN_IF_ERROR(SetUpHierarchy(header, kMaxBaseVertices, base, hierarchy).status());
  const SemiRegularHierarchy& h = *hierarchy;
  const PrecinctPartition partition =
      PartitionIntoPrecincts(h, base.grid, header.packets.precinct_coefficients);
  const int finest = levels - 1;
  out.finest_count_ = precincts.count(finest);
  out.ancestor_.resize(static_cast<size_t>(levels));
  for (uint32_t q = 0; q < out.finest_count_; ++q) {
    uint32_t p = q;
    for (int j = finest; j >= 0; --j) {
      out.ancestor_[static_cast<size_t>(j)].push_back(p);
      if (j > 0) p = precincts.parent(j, p);
    }
  }
  // Clusters: base faces (coarser ones judge a close camera's view far
  // less well), each in its face's finest precinct.
  const auto& base_faces = h.faces(0);
  out.cluster_precinct_ = partition.FacePrecincts(finest);
  const uint32_t clusters = static_cast<uint32_t>(base_faces.size());
  const std::vector<uint32_t> cluster_of_vertex = VertexBaseFaces(h);
  {
    std::vector<std::vector<uint32_t>> clusters_of(h.vertex_count(0));
    for (uint32_t f = 0; f < clusters; ++f) {
      for (uint32_t v : base_faces[f]) clusters_of[v].push_back(f);
    }
    // The finest precincts of the clusters around each cluster, but its
    // own: within a precinct every cluster's schedule counts anyway.
    std::vector<std::vector<uint32_t>> ring(clusters);
    for (uint32_t c = 0; c < clusters; ++c) {
      for (uint32_t v : base_faces[c]) {
        for (uint32_t g : clusters_of[v]) {
          const uint32_t q = out.cluster_precinct_[g];
          if (q != out.cluster_precinct_[c]) ring[c].push_back(q);
        }
      }
    }
    out.neighbour_first_.push_back(0);
    for (auto& r : ring) {
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
      out.neighbours_.insert(out.neighbours_.end(), r.begin(), r.end());
      out.neighbour_first_.push_back(static_cast<uint32_t>(out.neighbours_.size()));
    }
  }

  // The complete remesh and its normals; the rd order of its packets.
  std::vector<uint32_t> order;
  for (uint32_t id : PacketOrder(header, Progression::kRd)) {
    if (layout.IsChannel(id) || layout.IsTexture(id) || layout.IsOriginal(id)) continue;
    order.push_back(id);
  }
  MW_ASSIGN_OR_RETURN(auto d, ProgressiveDecoder::Create(header));
  for (uint32_t id : order) MW_RETURN_IF_ERROR(Add(*d, payloads, static_cast<int>(id)));
  const std::vector<Vec3> full = d->Positions();
  const std::vector<Vec3> normals = VertexNormals(d->Faces(), full, full.size());
  std::vector<float> complete_along(full.size());
  for (size_t v = 0; v < full.size(); ++v) {
    complete_along[v] = static_cast<float>(full[v].dot(normals[v]));
  }
  {
    std::vector<Vec3> lo(clusters, Vec3::Constant(INFINITY)), hi(clusters, Vec3::Constant(-INFINITY));
    for (size_t v = 0; v < full.size(); ++v) {
      const uint32_t c = cluster_of_vertex[v];
      lo[c] = lo[c].cwiseMin(full[v]);
      hi[c] = hi[c].cwiseMax(full[v]);
    }
    for (uint32_t c = 0; c < clusters; ++c) {
      const bool empty = !(lo[c].x() <= hi[c].x());
      out.centre_.push_back(empty ? Vec3::Zero() : Vec3(0.5 * (lo[c] + hi[c])));
      out.radius_.push_back(empty ? 0.0 : 0.5 * (hi[c] - lo[c]).norm());
    }
  }
  // State by state along the order.
  out.rank_.assign(payloads.size(), -1);
  std::vector<std::vector<float>> error(order.size() + 1, std::vector<float>(clusters, 0.0f));
  d->Reset();
  for (size_t k = 0; k <= order.size(); ++k) {
    if (k > 0) {
      out.rank_[order[k - 1]] = static_cast<int>(k - 1);
      MW_RETURN_IF_ERROR(Add(*d, payloads, static_cast<int>(order[k - 1])));
    }
    const std::vector<Vec3> got = d->Positions();
    std::vector<float>& row = error[k];
    for (size_t v = 0; v < got.size(); ++v) {
      const float e = std::abs(static_cast<float>(got[v].dot(normals[v])) - complete_along[v]);
      float& cell = row[cluster_of_vertex[v]];
      cell = std::max(cell, e);
    }
  }
  // "Or any later state": the largest from k on, so that a precinct once
  // within a tolerance stays within it.
  for (size_t k = order.size(); k-- > 0;) {
    for (uint32_t c = 0; c < clusters; ++c) {
      error[k][c] = std::max(error[k][c], error[k + 1][c]);
    }
  }
  // Bitplane by bitplane, from the header's base mesh alone.
  int top = layout.base_planes() - 1;
  for (int j = 0; j < layout.levels(); ++j) top = std::max(top, layout.Top(j));
  const int states = top + 2;
  std::vector<std::vector<float>> plane_error(static_cast<size_t>(states),
                          std::vector<float>(clusters, 0.0f));
  d->Reset();
  for (int b = states - 1; b >= 0; --b) {
    if (b < states - 1) {
      for (int j = 0; j < layout.levels(); ++j) {
        MW_RETURN_IF_ERROR(Add(*d, payloads, layout.Id(j, b)));
      }
      MW_RETURN_IF_ERROR(Add(*d, payloads, layout.BaseId(b)));
    }
    const std::vector<Vec3> got = d->Positions();
    std::vector<float>& row = plane_error[static_cast<size_t>(b)];
    for (size_t v = 0; v < got.size(); ++v) {
      const float e = std::abs(static_cast<float>(got[v].dot(normals[v])) - complete_along[v]);
      float& cell = row[cluster_of_vertex[v]];
      cell = std::max(cell, e);
    }
  }
  for (size_t b = 1; b < plane_error.size(); ++b) {
    for (uint32_t c = 0; c < clusters; ++c) {
      plane_error[b][c] = std::max(plane_error[b][c], plane_error[b - 1][c]);
    }
  }
  out.steps_ = static_cast<int>(order.size());
  out.planes_ = states - 1;
  out.error_.resize(static_cast<size_t>(clusters) * error.size());
  out.plane_error_.resize(static_cast<size_t>(clusters) * plane_error.size());
  for (uint32_t c = 0; c < clusters; ++c) {
    for (size_t k = 0; k < error.size(); ++k) out.error_[c * error.size() + k] = error[k][c];
    for (size_t b = 0; b < plane_error.size(); ++b) {
      out.plane_error_[c * plane_error.size() + b] = plane_error[b][c];
    }
  }
  return out;
}

}  // namespace meshwave
