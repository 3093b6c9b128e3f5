#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"
#include "entropy/context_model.h"

namespace meshwave {
namespace {

// One coded symbol: a context index, or kBypass for a p = 1/2 symbol.
constexpr int kBypass = -1;
struct Symbol {
  int context;
  int bit;
};

struct Encoded {
  std::string packet;
  double ideal_bits = 0;  // -sum log2 of the model's own probabilities
};

Encoded EncodeAll(const std::vector<Symbol>& symbols, int num_contexts) {
  std::vector<BinaryContext> contexts(num_contexts);
  ArithmeticEncoder encoder;
  Encoded out;
  for (const Symbol& s : symbols) {
    if (s.context == kBypass) {
      encoder.EncodeBypass(s.bit);
      out.ideal_bits += 1;
      continue;
    }
    const double p0 = contexts[s.context].probability() / 32768.0;
    out.ideal_bits -= std::log2(s.bit == 0 ? p0 : 1 - p0);
    encoder.Encode(s.bit, contexts[s.context]);
  }
  out.packet = encoder.Finish();
  return out;
}

struct Decoded {
  std::vector<int> bits;
  size_t padding_bytes = 0;
  bool overrun = false;
};

// Decodes as many symbols as `shape` lists, with its contexts.
Decoded DecodeAll(std::span<const uint8_t> packet,
                  const std::vector<Symbol>& shape, int num_contexts) {
  std::vector<BinaryContext> contexts(num_contexts);
  ArithmeticDecoder decoder(packet);
  Decoded out;
  out.bits.reserve(shape.size());
  for (const Symbol& s : shape) {
    out.bits.push_back(s.context == kBypass
                           ? decoder.DecodeBypass()
                           : decoder.Decode(contexts[s.context]));
  }
  out.padding_bytes = decoder.padding_bytes();
  out.overrun = decoder.overrun();
  return out;
}

std::vector<int> BitsOf(const std::vector<Symbol>& symbols) {
  std::vector<int> bits;
  for (const Symbol& s : symbols) bits.push_back(s.bit);
  return bits;
}

// Bytes in an allocation of exactly their size, so that ASan reports any
// read past the end.
class HeapBytes {
 public:
  explicit HeapBytes(std::string_view bytes)
      : data_(new uint8_t[bytes.size()]), size_(bytes.size()) {
    std::copy(bytes.begin(), bytes.end(), data_.get());
  }
  std::span<const uint8_t> span() const { return {data_.get(), size_}; }

 private:
  std::unique_ptr<uint8_t[]> data_;
  size_t size_;
};

// A random packet's symbols: `num_contexts` contexts with their own P(1),
// either uniform in [0, 1] or log-uniform in [1e-4, 0.5] (either polarity),
// and optionally one bypass symbol in four.
std::vector<Symbol> RandomSymbols(std::mt19937_64& rng, size_t count,
                                  int num_contexts, bool with_bypass) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> p1(num_contexts);
  for (double& p : p1) {
    if (rng() % 2) {
      p = unit(rng);
    } else {
      p = std::pow(10.0, -4 + 3.7 * unit(rng));
      if (rng() % 2) p = 1 - p;
    }
  }
  std::vector<Symbol> symbols(count);
  for (Symbol& s : symbols) {
    if (with_bypass && rng() % 4 == 0) {
      s = {kBypass, static_cast<int>(rng() % 2)};
    } else {
      const int c = static_cast<int>(rng() % num_contexts);
      s = {c, unit(rng) < p1[c] ? 1 : 0};
    }
  }
  return symbols;
}

std::string HexOf(std::string_view bytes) {
  std::string hex;
  char buf[3];
  for (unsigned char b : bytes) {
    std::snprintf(buf, sizeof(buf), "%02x", b);
    hex += buf;
  }
  return hex;
}

// ---------------------------------------------------------------------------
// Round trips

class RandomRoundTripTest : public testing::TestWithParam<uint64_t> {};

TEST_P(RandomRoundTripTest, DecodesRandomStreamsFromTheExactBytes) {
  std::mt19937_64 rng(GetParam());
  for (int stream = 0; stream < 500; ++stream) {
    const size_t count = rng() % 2 ? rng() % 51 : rng() % 5001;
    const int num_contexts = 1 + static_cast<int>(rng() % 64);
    const auto symbols = RandomSymbols(rng, count, num_contexts,
                                       /*with_bypass=*/stream % 3 == 0);
    const Encoded encoded = EncodeAll(symbols, num_contexts);
    const HeapBytes exact(encoded.packet);
    const Decoded decoded = DecodeAll(exact.span(), symbols, num_contexts);
    ASSERT_EQ(decoded.bits, BitsOf(symbols)) << "stream " << stream;
    EXPECT_FALSE(decoded.overrun);
    EXPECT_GE(decoded.padding_bytes, count == 0 ? 4u : 3u);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomRoundTripTest,
                         testing::Values(1, 2, 3, 20240611));

TEST(ArithmeticCoderTest, RoundTripsMixedBypassAndContextSymbols) {
  std::mt19937_64 rng(11);
  for (int stream = 0; stream < 200; ++stream) {
    const auto symbols = RandomSymbols(rng, rng() % 3000, 8, true);
    const Encoded encoded = EncodeAll(symbols, 8);
    const HeapBytes exact(encoded.packet);
    ASSERT_EQ(DecodeAll(exact.span(), symbols, 8).bits, BitsOf(symbols));
  }
}

TEST(ArithmeticCoderTest, EncodeBitsRoundTripsEveryWidth) {
  std::mt19937_64 rng(12);
  ArithmeticEncoder encoder;
  BinaryContext ctx;
  std::vector<std::pair<uint32_t, int>> fields;
  for (int round = 0; round < 20; ++round) {
    for (int width = 0; width <= 32; ++width) {
      const uint32_t mask =
          width == 32 ? 0xFFFFFFFFu : (uint32_t{1} << width) - 1;
      const uint32_t value = round == 0   ? mask
                             : round == 1 ? 0
                                          : static_cast<uint32_t>(rng()) & mask;
      // Bits above `width` are ignored.
      encoder.EncodeBits(value | ~mask, width);
      fields.emplace_back(value, width);
      encoder.Encode(round % 2, ctx);  // interleave a context symbol
    }
  }
  const std::string packet = encoder.Finish();
  const HeapBytes exact(packet);
  ArithmeticDecoder decoder(exact.span());
  BinaryContext dctx;
  int round = 0;
  for (size_t i = 0; i < fields.size(); ++i) {
    ASSERT_EQ(decoder.DecodeBits(fields[i].second), fields[i].first)
        << "width " << fields[i].second;
    ASSERT_EQ(decoder.Decode(dctx), round % 2);
    if (fields[i].second == 32) ++round;
  }
  EXPECT_FALSE(decoder.overrun());
}

TEST(ArithmeticCoderTest, EmptyStreamFinishesToAnEmptyPacket) {
  ArithmeticEncoder encoder;
  EXPECT_EQ(encoder.Finish(), "");
  ArithmeticDecoder decoder(std::span<const uint8_t>{});
  EXPECT_FALSE(decoder.overrun());
  EXPECT_EQ(decoder.padding_bytes(), 4u);  // the code register's bytes
}

TEST(ArithmeticCoderTest, StripsTrailingZeroBytes) {
  // Only 0-bits keep the code value at 0: nothing needs to be sent.
  std::vector<Symbol> zeros(200, Symbol{0, 0});
  const Encoded encoded = EncodeAll(zeros, 1);
  EXPECT_EQ(encoded.packet, "");
  EXPECT_EQ(DecodeAll({}, zeros, 1).bits, BitsOf(zeros));
  // No packet ends in 0x00 unless the padding budget stopped the stripping.
  std::mt19937_64 rng(13);
  for (int stream = 0; stream < 1000; ++stream) {
    const auto symbols = RandomSymbols(rng, rng() % 2000, 4, false);
    const Encoded e = EncodeAll(symbols, 4);
    if (e.packet.empty() || e.packet.back() != '\0') continue;
    const HeapBytes exact(e.packet);
    EXPECT_EQ(DecodeAll(exact.span(), symbols, 4).padding_bytes,
              kMaxPaddingBytes);
  }
}

TEST(ArithmeticCoderTest, EncoderStartsAfreshAfterFinish) {
  std::mt19937_64 rng(14);
  const auto first = RandomSymbols(rng, 500, 4, true);
  const auto second = RandomSymbols(rng, 700, 4, true);
  ArithmeticEncoder reused;
  for (const auto* symbols : {&first, &second}) {
    std::vector<BinaryContext> contexts(4);
    for (const Symbol& s : *symbols) {
      if (s.context == kBypass) {
        reused.EncodeBypass(s.bit);
      } else {
        reused.Encode(s.bit, contexts[s.context]);
      }
    }
    EXPECT_EQ(reused.Finish(), EncodeAll(*symbols, 4).packet);
  }
}

// Pins the byte format (context_model.h, docs/FORMAT.md): a change here
// breaks every stored stream.
TEST(ArithmeticCoderTest, EncodesTheDocumentedBytes) {
  ArithmeticEncoder encoder;
  BinaryContext a, b;
  const int bits_a[] = {0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 0};
  for (int i = 0; i < 16; ++i) {
    encoder.Encode(bits_a[i], a);
    encoder.Encode(i % 3 == 0 ? 1 : 0, b);
  }
  encoder.EncodeBits(0xC0FFEE, 24);
  encoder.EncodeBypass(1);
  for (int i = 0; i < 40; ++i) encoder.Encode(0, a);
  const std::string packet = encoder.Finish();
  // Also what a big-integer encoder written from the format text gives.
  EXPECT_EQ(HexOf(packet), "4a6cd35a99ca735b33");

  ArithmeticDecoder decoder(packet);
  BinaryContext da, db;
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(decoder.Decode(da), bits_a[i]);
    EXPECT_EQ(decoder.Decode(db), i % 3 == 0 ? 1 : 0);
  }
  EXPECT_EQ(decoder.DecodeBits(24), 0xC0FFEEu);
  EXPECT_EQ(decoder.DecodeBypass(), 1);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(decoder.Decode(da), 0);
  EXPECT_FALSE(decoder.overrun());
}

// A decoder written from the format text alone (context_model.h), with the
// update formula computed instead of tabled: it must agree with
// ArithmeticDecoder on every symbol, so the text is complete and exact.
class FormatTextDecoder {
 public:
  explicit FormatTextDecoder(std::string_view packet) : bytes_(packet) {
    for (int i = 0; i < 4; ++i) code_ = code_ << 8 | Next();
  }
  int Decode(uint32_t& p, uint32_t& n) {
    const uint32_t q = p >> 1;
    const uint32_t bound =
        static_cast<uint32_t>((static_cast<uint64_t>(range_) * q) >> 15);
    const int bit = Choose(bound);
    const uint32_t r = 65535 / (std::min(n, 30u) + 2);
    if (bit == 0) {
      p += ((65536 - p) * r) >> 16;
    } else {
      p -= (p * r) >> 16;
    }
    n = std::min(n + 1, 30u);
    Normalise();
    return bit;
  }
  int DecodeBypass() {
    const int bit = Choose(range_ >> 1);
    Normalise();
    return bit;
  }

 private:
  int Choose(uint32_t bound) {
    if (code_ < bound) {
      range_ = bound;
      return 0;
    }
    code_ -= bound;
    range_ -= bound;
    return 1;
  }
  void Normalise() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = code_ << 8 | Next();
    }
  }
  uint32_t Next() {
    return pos_ < bytes_.size() ? static_cast<uint8_t>(bytes_[pos_++]) : 0;
  }

  std::string_view bytes_;
  size_t pos_ = 0;
  uint32_t code_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
};

TEST(ArithmeticCoderTest, MatchesADecoderWrittenFromTheFormatText) {
  std::mt19937_64 rng(15);
  for (int stream = 0; stream < 300; ++stream) {
    const auto symbols = RandomSymbols(rng, rng() % 3000, 16, true);
    const Encoded encoded = EncodeAll(symbols, 16);
    FormatTextDecoder reference(encoded.packet);
    std::vector<uint32_t> p(16, 32768), n(16, 0);
    std::vector<int> bits;
    for (const Symbol& s : symbols) {
      bits.push_back(s.context == kBypass
                         ? reference.DecodeBypass()
                         : reference.Decode(p[s.context], n[s.context]));
    }
    ASSERT_EQ(bits, BitsOf(symbols)) << "stream " << stream;
  }
}

// ---------------------------------------------------------------------------
// Termination and bounds

// The decoder over a sub-span of a larger buffer whose next bytes are 0xFF
// must give what it gives over an exact copy: it never looks past the end.
// The last check shows that those bytes would matter: decoded as part of the
// packet they change the symbols of many packets.
TEST(ArithmeticDecoderTest, NeverReadsPastThePacketEnd) {
  std::mt19937_64 rng(16);
  int differ_if_read = 0;
  for (int stream = 0; stream < 1000; ++stream) {
    const auto symbols = RandomSymbols(rng, rng() % 400, 4, stream % 2 == 0);
    const std::string packet = EncodeAll(symbols, 4).packet;
    const HeapBytes exact(packet);
    const Decoded from_exact = DecodeAll(exact.span(), symbols, 4);

    const HeapBytes buffer(packet + std::string(16, '\xFF'));
    const Decoded from_sub_span =
        DecodeAll(buffer.span().first(packet.size()), symbols, 4);
    ASSERT_EQ(from_sub_span.bits, from_exact.bits);
    ASSERT_EQ(from_sub_span.padding_bytes, from_exact.padding_bytes);
    ASSERT_EQ(from_exact.bits, BitsOf(symbols));

    if (DecodeAll(buffer.span(), symbols, 4).bits != from_exact.bits) {
      ++differ_if_read;
    }
  }
  EXPECT_GT(differ_if_read, 20);
}

// Every prefix of a packet, each in its own allocation: decoding the full
// symbol count never reads outside it, and a proper prefix never passes for
// the packet. The minimal flush makes that exact: a shorter code value with
// the same symbols would have been the flush's choice, and zeros kept only
// for the padding budget leave no padding to spare.
TEST(ArithmeticDecoderTest, DetectsEveryTruncatedPacket) {
  std::mt19937_64 rng(17);
  for (int stream = 0; stream < 60; ++stream) {
    const auto symbols =
        RandomSymbols(rng, rng() % 1500, 1 + stream % 8, stream % 2 == 0);
    const int num_contexts = 1 + stream % 8;
    const std::string packet = EncodeAll(symbols, num_contexts).packet;
    for (size_t length = 0; length <= packet.size(); ++length) {
      const HeapBytes prefix(std::string_view(packet).substr(0, length));
      const Decoded decoded = DecodeAll(prefix.span(), symbols, num_contexts);
      if (length == packet.size()) {
        EXPECT_EQ(decoded.bits, BitsOf(symbols));
        EXPECT_FALSE(decoded.overrun);
      } else {
        EXPECT_TRUE(decoded.overrun || decoded.bits != BitsOf(symbols))
            << "stream " << stream << " prefix " << length << " of "
            << packet.size();
      }
    }
  }
}

TEST(ArithmeticDecoderTest, ReportsOverrunWhenDecodingMoreThanWasEncoded) {
  std::mt19937_64 rng(18);
  for (int stream = 0; stream < 100; ++stream) {
    auto symbols = RandomSymbols(rng, rng() % 1000, 4, false);
    const std::string packet = EncodeAll(symbols, 4).packet;
    const HeapBytes exact(packet);
    EXPECT_FALSE(DecodeAll(exact.span(), symbols, 4).overrun);
    // 12 bytes' worth of extra bypass symbols need padding beyond the budget.
    symbols.insert(symbols.end(), 96, Symbol{kBypass, 0});
    EXPECT_TRUE(DecodeAll(exact.span(), symbols, 4).overrun);
  }
}

TEST(ArithmeticDecoderTest, DecodesRandomBytesWithoutFailing) {
  std::mt19937_64 rng(19);
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bytes(rng() % 64, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    if (trial % 4 == 0) bytes.assign(bytes.size(), '\xFF');
    const HeapBytes heap(bytes);
    ArithmeticDecoder decoder(heap.span());
    BinaryContext contexts[3];
    int ones = 0;
    for (int i = 0; i < 2000; ++i) {
      ones +=
          i % 7 == 0 ? decoder.DecodeBypass() : decoder.Decode(contexts[i % 3]);
    }
    ones += static_cast<int>(decoder.DecodeBits(32) & 1);
    EXPECT_LE(ones, 2001);
  }
}

// The branch-free decode is the same decoder: over random bytes (so every
// path, context state and padding read is met) it gives the very symbols,
// contexts and padding that Decode gives.
TEST(ArithmeticDecoderTest, UnpredictableDecodeMatchesDecode) {
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 500; ++trial) {
    std::string bytes(rng() % 96, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    const HeapBytes heap(bytes);
    ArithmeticDecoder a(heap.span()), b(heap.span());
    BinaryContext ca[4], cb[4];
    for (int i = 0; i < 1500; ++i) {
      const int k = static_cast<int>(rng() % 4);
      const bool unpredictable = rng() % 2 == 0;
      const int x = a.Decode(ca[k]);
      const int y = unpredictable ? b.DecodeUnpredictable(cb[k]) : b.Decode(cb[k]);
      ASSERT_EQ(x, y) << "trial " << trial << " symbol " << i;
      ASSERT_EQ(ca[k].probability(), cb[k].probability());
    }
    EXPECT_EQ(a.padding_bytes(), b.padding_bytes());
  }
}

// The symbols a decoder reads from `target` (zero-padded) with the contexts
// of `shape`: their intervals all contain the target value.
std::vector<Symbol> SymbolsAround(std::string_view target,
                                  std::vector<Symbol> shape, int num_contexts) {
  const Decoded decoded = DecodeAll(
      {reinterpret_cast<const uint8_t*>(target.data()), target.size()}, shape,
      num_contexts);
  for (size_t i = 0; i < shape.size(); ++i) shape[i].bit = decoded.bits[i];
  return shape;
}

size_t LongestRunOfFF(std::string_view bytes) {
  size_t longest = 0;
  size_t run = 0;
  for (char c : bytes) {
    run = c == '\xFF' ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

// Intervals that close in on 1/2 from below make the encoder's low read
// 0.7F FF FF ...: a long run of 0xFF bytes held back for a carry. The flush
// picks 1/2 itself, and the carry turns the run into 0x80 00 00 ...
TEST(ArithmeticCoderTest, CarriesThroughLongRunsOfFF) {
  std::mt19937_64 rng(20);
  int long_carries = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int num_contexts = 1 + trial % 4;
    const auto symbols = SymbolsAround(
        "\x80", RandomSymbols(rng, 3000, num_contexts, true), num_contexts);
    // Information before the last 1-bit: while the interval still lay below
    // 1/2, its low end had about that many bits of 0xFF after the 0x7F.
    std::vector<BinaryContext> contexts(num_contexts);
    double bits_before_last_one = 0;
    double bits = 0;
    for (const Symbol& s : symbols) {
      if (s.bit == 1) bits_before_last_one = bits;
      if (s.context == kBypass) {
        bits += 1;
      } else {
        const double p0 = contexts[s.context].probability() / 32768.0;
        bits -= std::log2(s.bit == 0 ? p0 : 1 - p0);
        contexts[s.context].Update(s.bit);
      }
    }
    const std::string packet = EncodeAll(symbols, num_contexts).packet;
    const HeapBytes exact(packet);
    const Decoded decoded = DecodeAll(exact.span(), symbols, num_contexts);
    ASSERT_EQ(decoded.bits, BitsOf(symbols)) << "trial " << trial;
    EXPECT_FALSE(decoded.overrun);
    // 0x80 then the zeros the padding budget keeps.
    ASSERT_FALSE(packet.empty());
    EXPECT_EQ(packet[0], '\x80');
    EXPECT_EQ(packet.find_first_not_of('\0', 1), std::string::npos);
    if (bits_before_last_one >= 8 * 100) ++long_carries;
  }
  EXPECT_GE(long_carries, 10);
}

// Intervals around 0.7F FF ... FF (150 bytes of 0xFF) narrowed to less than
// 256^-150 never reach 1/2: the held run leaves as it is, without a carry.
TEST(ArithmeticCoderTest, ReleasesLongRunsOfFFWithoutCarry) {
  std::mt19937_64 rng(21);
  // Built in place: GCC 12 reports a false -Warray-bounds in an inlined
  // operator+(const char*, std::string&&) here.
  std::string target(151, '\xFF');
  target[0] = '\x7F';
  for (int trial = 0; trial < 10; ++trial) {
    const int num_contexts = 1 + trial % 4;
    // About 2,000 bypass symbols: more than 150 bytes of information.
    const auto symbols = SymbolsAround(
        target, RandomSymbols(rng, 8000, num_contexts, true), num_contexts);
    const std::string packet = EncodeAll(symbols, num_contexts).packet;
    const HeapBytes exact(packet);
    const Decoded decoded = DecodeAll(exact.span(), symbols, num_contexts);
    ASSERT_EQ(decoded.bits, BitsOf(symbols)) << "trial " << trial;
    EXPECT_FALSE(decoded.overrun);
    ASSERT_FALSE(packet.empty());
    EXPECT_EQ(packet[0], '\x7F');
    EXPECT_GE(LongestRunOfFF(packet), 150u);
  }
}

// ---------------------------------------------------------------------------
// Efficiency

TEST(ArithmeticCoderTest, RunOfOneSymbolCostsItsModelEntropy) {
  for (int bit = 0; bit <= 1; ++bit) {
    const std::vector<Symbol> run(100000, Symbol{0, bit});
    const Encoded encoded = EncodeAll(run, 1);
    EXPECT_LE(encoded.packet.size(), encoded.ideal_bits / 8 * 1.01 + 8)
        << "bit " << bit << " ideal " << encoded.ideal_bits / 8;
    const HeapBytes exact(encoded.packet);
    EXPECT_EQ(DecodeAll(exact.span(), run, 1).bits, BitsOf(run));
  }
}

TEST(ArithmeticCoderTest, SkewedSourceCostsItsModelEntropy) {
  std::mt19937_64 rng(23);
  std::bernoulli_distribution lps(0.001);
  for (int polarity = 0; polarity <= 1; ++polarity) {
    std::vector<Symbol> symbols(100000);
    for (Symbol& s : symbols) s = {0, lps(rng) ? 1 - polarity : polarity};
    const Encoded encoded = EncodeAll(symbols, 1);
    EXPECT_LE(encoded.packet.size(), encoded.ideal_bits / 8 * 1.01 + 8)
        << "ideal " << encoded.ideal_bits / 8;
    const HeapBytes exact(encoded.packet);
    EXPECT_EQ(DecodeAll(exact.span(), symbols, 1).bits, BitsOf(symbols));
  }
}

// LZMA's 5-byte flush costs about 4 bytes more than the
// minimal one. Measured here: about 0.3 bytes beyond the ideal code length.
TEST(ArithmeticCoderTest, FlushCostsUnderTwoBytesPerPacket) {
  std::mt19937_64 rng(22);
  constexpr int kPackets = 3000;
  double overhead = 0;
  for (int packet = 0; packet < kPackets; ++packet) {
    const auto symbols =
        RandomSymbols(rng, rng() % 301, 1 + packet % 8, packet % 4 == 0);
    const Encoded encoded = EncodeAll(symbols, 1 + packet % 8);
    overhead +=
        static_cast<double>(encoded.packet.size()) - encoded.ideal_bits / 8;
  }
  const double mean = overhead / kPackets;
  RecordProperty("mean_flush_overhead_bytes", std::to_string(mean));
  std::printf("mean flush overhead: %.3f bytes per packet\n", mean);
  EXPECT_LE(mean, 2.0);
}

}  // namespace
}  // namespace meshwave
