// ByteReader: a bounded cursor over untrusted bytes. Every read states how
// many bytes it needs and fails, without moving, when fewer remain; callers
// turn a failure into a ParseError that names what they were reading.
#ifndef MESHWAVE_CORE_BYTE_READER_H_
#define MESHWAVE_CORE_BYTE_READER_H_

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <type_traits>

namespace meshwave {

// Reverses the bytes of an arithmetic value (integer or IEEE float).
template <class T>
T ByteSwapped(T value) {
  static_assert(std::is_arithmetic_v<T>);
  if constexpr (sizeof(T) == 1) {
    return value;
  } else if constexpr (sizeof(T) == 2) {
    return std::bit_cast<T>(__builtin_bswap16(std::bit_cast<uint16_t>(value)));
  } else if constexpr (sizeof(T) == 4) {
    return std::bit_cast<T>(__builtin_bswap32(std::bit_cast<uint32_t>(value)));
  } else {
    static_assert(sizeof(T) == 8);
    return std::bit_cast<T>(__builtin_bswap64(std::bit_cast<uint64_t>(value)));
  }
}

// Loads a T stored at `p` (no alignment needed) in byte order `order`. The
// caller has already checked that sizeof(T) bytes are readable at `p`.
template <class T>
T LoadUnaligned(const char* p, std::endian order) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return order == std::endian::native ? value : ByteSwapped(value);
}

// Returns a * b, or nullopt when the product does not fit in size_t.
inline std::optional<size_t> CheckedMul(size_t a, size_t b) {
  size_t product = 0;
  if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
  return product;
}

class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

  size_t position() const { return position_; }
  size_t remaining() const { return bytes_.size() - position_; }
  bool empty() const { return remaining() == 0; }
  std::string_view rest() const { return bytes_.substr(position_); }

  // Takes the next `n` bytes as a view into the input; false if fewer remain.
  bool ReadBytes(size_t n, std::string_view* out) {
    if (n > remaining()) return false;
    *out = bytes_.substr(position_, n);
    position_ += n;
    return true;
  }

  bool Skip(size_t n) {
    if (n > remaining()) return false;
    position_ += n;
    return true;
  }

  // Reads one T in byte order `order`; false if fewer than sizeof(T) remain.
  template <class T>
  bool Read(std::endian order, T* out) {
    if (sizeof(T) > remaining()) return false;
    *out = LoadUnaligned<T>(bytes_.data() + position_, order);
    position_ += sizeof(T);
    return true;
  }

 private:
  std::string_view bytes_;
  size_t position_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_BYTE_READER_H_
