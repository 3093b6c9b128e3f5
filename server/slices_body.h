// A Beast body made of an owned prefix (a container header, a JSON text)
// followed by slices of memory owned elsewhere (payloads in a container's
// memory map), kept alive by the mesh's shared_ptr for as long as the
// response exists. Payload bytes are handed to the socket without being
// copied (HttpSession writes head, prefix and slices in one gathered write).
#ifndef MESHWAVE_SERVER_SLICES_BODY_H_
#define MESHWAVE_SERVER_SLICES_BODY_H_

#include <boost/optional.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "net.h"

namespace meshwave::server {

class ServedMesh;

struct SlicesBody {
  struct value_type {
    std::string owned;                       // sent first
    std::vector<net::const_buffer> slices;   // then these, in order
    // Owns the slices' bytes; set by the mesh endpoints, whose successful
    // responses the ResponseCache may keep.
    std::shared_ptr<const ServedMesh> mesh;

    void AddSlice(std::string_view bytes) {
      if (!bytes.empty()) slices.emplace_back(bytes.data(), bytes.size());
    }
    uint64_t size() const {
      uint64_t n = owned.size();
      for (const auto& s : slices) n += s.size();
      return n;
    }
  };

  static uint64_t size(const value_type& body) { return body.size(); }

  class writer {
   public:
    using const_buffers_type = std::vector<net::const_buffer>;

    template <bool isRequest, class Fields>
    writer(const http::header<isRequest, Fields>&, const value_type& body)
        : body_(body) {}

    void init(beast::error_code& ec) { ec = {}; }

    boost::optional<std::pair<const_buffers_type, bool>> get(beast::error_code& ec) {
      ec = {};
      if (done_) return boost::none;
      done_ = true;
      const_buffers_type buffers;
      buffers.reserve(body_.slices.size() + 1);
      if (!body_.owned.empty()) buffers.emplace_back(body_.owned.data(), body_.owned.size());
      buffers.insert(buffers.end(), body_.slices.begin(), body_.slices.end());
      return std::make_pair(std::move(buffers), false);
    }

   private:
    const value_type& body_;
    bool done_ = false;
  };
};

using Request = http::request<http::string_body>;
using Response = http::response<SlicesBody>;

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SLICES_BODY_H_
