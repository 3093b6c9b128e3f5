// SHA-256 of a byte string (OpenSSL EVP), as lowercase hex: the content
// address of a container and the root of its ETags.
#ifndef MESHWAVE_SERVER_SHA256_H_
#define MESHWAVE_SERVER_SHA256_H_

#include <string>
#include <string_view>

namespace meshwave::server {

// 64 lowercase hex digits.
std::string Sha256Hex(std::string_view bytes);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SHA256_H_
