// Throughput of the binary arithmetic coder in symbols per second (one
// core): a skewed source like bitplane significance symbols (16 contexts,
// P(1) from 0.01 to 0.2: entropy 0.317, coded 0.331 bits per symbol), an
// unpredictable one (P(1) 0.4 to 0.6: every branch a coin toss) and raw
// bypass bits.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"
#include "entropy/context_model.h"

namespace meshwave {
namespace {

constexpr int kContexts = 16;
constexpr size_t kSymbols = 1 << 20;

struct Source {
  std::vector<uint8_t> context;
  std::vector<uint8_t> bit;
  std::string packet;
};

// `skewed`: P(1) of context c is 0.01 * 20^(c / 15); else 0.4 to 0.6.
Source MakeSource(bool skewed) {
  Source source;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> p1(kContexts);
  for (int c = 0; c < kContexts; ++c) {
    p1[c] = skewed ? 0.01 * std::pow(20.0, c / 15.0) : 0.4 + 0.2 * c / 15.0;
  }
  source.context.resize(kSymbols);
  source.bit.resize(kSymbols);
  ArithmeticEncoder encoder;
  std::vector<BinaryContext> contexts(kContexts);
  for (size_t i = 0; i < kSymbols; ++i) {
    source.context[i] = static_cast<uint8_t>(rng() % kContexts);
    source.bit[i] = unit(rng) < p1[source.context[i]] ? 1 : 0;
    encoder.Encode(source.bit[i], contexts[source.context[i]]);
  }
  source.packet = encoder.Finish();
  return source;
}

const Source& Skewed() {
  static const Source source = MakeSource(true);
  return source;
}

const Source& Unpredictable() {
  static const Source source = MakeSource(false);
  return source;
}

void Encode(benchmark::State& state, const Source& source) {
  for (auto _ : state) {
    ArithmeticEncoder encoder;
    std::vector<BinaryContext> contexts(kContexts);
    for (size_t i = 0; i < kSymbols; ++i) {
      encoder.Encode(source.bit[i], contexts[source.context[i]]);
    }
    benchmark::DoNotOptimize(encoder.Finish());
  }
  state.SetItemsProcessed(state.iterations() * kSymbols);
  state.counters["bits_per_symbol"] =
      8.0 * static_cast<double>(source.packet.size()) / kSymbols;
}

void Decode(benchmark::State& state, const Source& source) {
  for (auto _ : state) {
    ArithmeticDecoder decoder(source.packet);
    std::vector<BinaryContext> contexts(kContexts);
    uint32_t ones = 0;
    for (size_t i = 0; i < kSymbols; ++i) {
      ones +=
          static_cast<uint32_t>(decoder.Decode(contexts[source.context[i]]));
    }
    benchmark::DoNotOptimize(ones);
  }
  state.SetItemsProcessed(state.iterations() * kSymbols);
}

void BM_EncodeSkewed(benchmark::State& state) { Encode(state, Skewed()); }
void BM_DecodeSkewed(benchmark::State& state) { Decode(state, Skewed()); }
void BM_EncodeUnpredictable(benchmark::State& state) {
  Encode(state, Unpredictable());
}
void BM_DecodeUnpredictable(benchmark::State& state) {
  Decode(state, Unpredictable());
}

// Bypass symbols, 8 at a time through EncodeBits / DecodeBits.
void BM_EncodeBits(benchmark::State& state) {
  for (auto _ : state) {
    ArithmeticEncoder encoder;
    for (size_t i = 0; i < kSymbols / 8; ++i) {
      encoder.EncodeBits(static_cast<uint32_t>(i * 0x9E), 8);
    }
    benchmark::DoNotOptimize(encoder.Finish());
  }
  state.SetItemsProcessed(state.iterations() * kSymbols);
}

void BM_DecodeBits(benchmark::State& state) {
  ArithmeticEncoder encoder;
  for (size_t i = 0; i < kSymbols / 8; ++i) {
    encoder.EncodeBits(static_cast<uint32_t>(i * 0x9E), 8);
  }
  const std::string packet = encoder.Finish();
  for (auto _ : state) {
    ArithmeticDecoder decoder(packet);
    uint32_t sum = 0;
    for (size_t i = 0; i < kSymbols / 8; ++i) sum += decoder.DecodeBits(8);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kSymbols);
}

BENCHMARK(BM_EncodeSkewed)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeSkewed)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodeUnpredictable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeUnpredictable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodeBits)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeBits)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshwave
