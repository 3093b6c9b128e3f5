// BitCast: std::bit_cast for the decoder's sources, which the WebAssembly
// build's libc++ (emscripten 3.1.6) does not have yet.
#ifndef MESHWAVE_CORE_BIT_CAST_H_
#define MESHWAVE_CORE_BIT_CAST_H_

#include <cstring>
#include <type_traits>

namespace meshwave {

template <class To, class From>
To BitCast(const From& from) {
  static_assert(sizeof(To) == sizeof(From));
  static_assert(std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>);
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_BIT_CAST_H_
