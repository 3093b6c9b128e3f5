// The two CRCs of the stream format, table-driven (Sarwate, "Computation of
// cyclic redundancy checks via table look-up", CACM 1988). Hand-written
// rather than Boost.CRC so that the decoder needs no Boost (WebAssembly).
#ifndef MESHWAVE_CORE_CRC_H_
#define MESHWAVE_CORE_CRC_H_

#include <array>
#include <cstdint>
#include <string_view>

namespace meshwave {
namespace crc_internal {

// MSB-first 16-bit table for polynomial 0x1021.
constexpr std::array<uint16_t, 256> MakeCrc16Table() {
  std::array<uint16_t, 256> t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i << 8;
    for (int k = 0; k < 8; ++k) c = (c & 0x8000) ? (c << 1) ^ 0x1021 : c << 1;
    t[i] = static_cast<uint16_t>(c);
  }
  return t;
}
// LSB-first (reflected) 32-bit table for polynomial 0x1EDC6F41 (0x82F63B78
// reflected).
constexpr std::array<uint32_t, 256> MakeCrc32cTable() {
  std::array<uint32_t, 256> t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    t[i] = c;
  }
  return t;
}
inline constexpr auto kCrc16Table = MakeCrc16Table();
inline constexpr auto kCrc32cTable = MakeCrc32cTable();

}  // namespace crc_internal

// CRC-16/CCITT-FALSE: polynomial 0x1021, init 0xFFFF, not reflected, no
// final xor (check value of "123456789": 0x29B1).
inline uint16_t Crc16CcittFalse(std::string_view bytes) {
  uint16_t crc = 0xFFFF;
  for (char ch : bytes) {
    const auto b = static_cast<uint8_t>(ch);
    crc = static_cast<uint16_t>((crc << 8) ^ crc_internal::kCrc16Table[((crc >> 8) ^ b) & 0xff]);
  }
  return crc;
}

// CRC-32C (Castagnoli): reflected, init and final xor 0xFFFFFFFF (check
// value of "123456789": 0xE3069283).
inline uint32_t Crc32c(std::string_view bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (char ch : bytes) {
    crc = (crc >> 8) ^ crc_internal::kCrc32cTable[(crc ^ static_cast<uint8_t>(ch)) & 0xff];
  }
  return crc ^ 0xFFFFFFFFu;
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_CRC_H_
