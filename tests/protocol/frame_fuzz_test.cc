// A bounded, deterministic mutation fuzzer over the FrameDecoder: valid
// streams of every message, mutated by bit flips, byte changes, truncations,
// insertions, deletions and length-prefix corruption, then decoded in several
// chunkings. Every run must end in messages or a clear error, never a crash,
// and the outcome must not depend on how the bytes were chunked.
// TESSERA_FUZZ_SEED overrides the fixed seed to explore further.
#include <gtest/gtest.h>

#include <google/protobuf/stubs/logging.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <random>

#include "protocol/framing.h"
#include "protocol/sample_messages.h"

namespace tessera {
namespace {

constexpr int kMutatedStreams = 4000;
constexpr uint32_t kFuzzMaxFrameBytes = 4096;

struct Corpus {
  std::string stream;
  std::vector<size_t> frameStarts;
};

template <typename Envelope>
Corpus encodeCorpus(const std::vector<Envelope>& messages) {
  Corpus corpus;
  for (const Envelope& message : messages) {
    corpus.frameStarts.push_back(corpus.stream.size());
    corpus.stream += encodeFrame(message).value();
  }
  return corpus;
}

uint32_t corruptLength(std::mt19937_64& rng) {
  switch (rng() % 6) {
    case 0:
      return 0;
    case 1:
      return 0xffffffffu;
    case 2:
      return kFuzzMaxFrameBytes;
    case 3:
      return kFuzzMaxFrameBytes + 1;
    case 4:
      return static_cast<uint32_t>(rng() % 64);
    default:
      return static_cast<uint32_t>(rng());
  }
}

std::string mutate(const Corpus& corpus, std::mt19937_64& rng) {
  std::string data = corpus.stream;
  const int mutations = 1 + static_cast<int>(rng() % 3);
  for (int m = 0; m < mutations && !data.empty(); ++m) {
    const size_t at = rng() % data.size();
    switch (rng() % 7) {
      case 0:
        data[at] = static_cast<char>(data[at] ^ (1 << (rng() % 8)));
        break;
      case 1:
        data[at] = static_cast<char>(rng());
        break;
      case 2:
        data.resize(at);
        break;
      case 3:
        data.erase(at, 1 + rng() % 8);
        break;
      case 4:
        data.insert(at, std::string(1 + rng() % 8, static_cast<char>(rng())));
        break;
      case 5:
        data.insert(at, data.substr(rng() % data.size(), 1 + rng() % 16));
        break;
      default: {
        // Rewrite one frame's length prefix (while the frame is still where it was).
        const size_t start = corpus.frameStarts[rng() % corpus.frameStarts.size()];
        if (start + kFrameHeaderBytes > data.size()) break;
        const uint32_t length = corruptLength(rng);
        for (size_t i = 0; i < kFrameHeaderBytes; ++i) {
          data[start + i] = static_cast<char>(length >> (8 * (kFrameHeaderBytes - 1 - i)));
        }
      }
    }
  }
  return data;
}

struct Outcome {
  std::vector<std::string> messages;  // re-serialized, for comparison
  FrameError error = FrameError::kNone;
  std::string errorMessage;
};

template <typename Envelope>
Outcome decode(const std::string& data, const std::vector<size_t>& chunkSizes) {
  FrameDecoder decoder({.maxFrameBytes = kFuzzMaxFrameBytes});
  Outcome outcome;
  Envelope message;
  size_t pos = 0;
  size_t chunk = 0;
  bool stop = false;
  while (!stop) {
    const size_t size = std::min(chunkSizes[chunk++ % chunkSizes.size()], data.size() - pos);
    (void)decoder.feed(std::string_view(data).substr(pos, size));  // next() reports any failure
    pos += size;
    while (true) {
      auto got = decoder.next(message);
      if (!got.isOk()) {
        stop = true;
        break;
      }
      if (!*got) break;
      outcome.messages.push_back(message.SerializeAsString());
    }
    if (pos == data.size()) break;
  }
  if (!stop) (void)decoder.finish();
  outcome.error = decoder.error();
  outcome.errorMessage = decoder.status().message();
  return outcome;
}

template <typename Envelope>
void fuzz(const Corpus& corpus, uint64_t seed, std::map<FrameError, int>& seen) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < kMutatedStreams; ++i) {
    const std::string data = mutate(corpus, rng);
    const Outcome whole = decode<Envelope>(data, {data.size() + 1});
    std::vector<size_t> randomChunks(5);
    for (size_t& size : randomChunks) size = 1 + rng() % 40;
    const Outcome chunked = decode<Envelope>(data, randomChunks);
    ++seen[whole.error];

    SCOPED_TRACE("mutated stream " + std::to_string(i) + " of seed " + std::to_string(seed));
    if (whole.error == FrameError::kNone) {
      EXPECT_TRUE(whole.errorMessage.empty());
    } else {
      EXPECT_NE(whole.errorMessage.find("frame "), std::string::npos) << whole.errorMessage;
    }
    ASSERT_EQ(chunked.error, whole.error) << whole.errorMessage << " vs " << chunked.errorMessage;
    ASSERT_EQ(chunked.errorMessage, whole.errorMessage);
    ASSERT_EQ(chunked.messages, whole.messages);
    if (i % 4 == 0) {  // byte at a time is the slowest; a sample is enough
      const Outcome bytewise = decode<Envelope>(data, {1});
      ASSERT_EQ(bytewise.errorMessage, whole.errorMessage);
      ASSERT_EQ(bytewise.messages, whole.messages);
    }
  }
}

uint64_t fuzzSeed() {
  const char* env = std::getenv("TESSERA_FUZZ_SEED");
  return env ? std::strtoull(env, nullptr, 10) : 20240611;
}

TEST(ProtocolFrameFuzz, MutatedStreamsGiveMessagesOrClearErrors) {
  google::protobuf::LogSilencer quiet;  // mutated strings trip protobuf's UTF-8 log
  const auto start = std::chrono::steady_clock::now();
  std::map<FrameError, int> seen;
  fuzz<wire::ClientMessage>(encodeCorpus(testing::sampleClientMessages()), fuzzSeed(), seen);
  fuzz<wire::ServerMessage>(encodeCorpus(testing::sampleServerMessages()), fuzzSeed() + 1, seen);

  // The mutations must reach every way a stream can fail, or the fuzzer is
  // not testing what it claims to.
  for (FrameError kind : {FrameError::kNone, FrameError::kZeroLength, FrameError::kTooLarge,
                          FrameError::kTruncated, FrameError::kBadPayload}) {
    EXPECT_GT(seen[kind], 0) << "no mutated stream ended in: " << frameErrorName(kind);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 8.0) << "the fuzzer must keep the suite fast";
}

}  // namespace
}  // namespace tessera
