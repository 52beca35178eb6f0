// Framing round trips: every command and reply through encodeFrame and the
// FrameDecoder, whole, split at every byte boundary and one byte at a time.
#include <gtest/gtest.h>

#include <google/protobuf/util/message_differencer.h>

#include "protocol/framing.h"
#include "protocol/sample_messages.h"
#include "protocol/tessera.pb.h"

namespace tessera {
namespace {

using google::protobuf::util::MessageDifferencer;

template <typename Envelope>
std::string encodeAll(const std::vector<Envelope>& messages) {
  std::string stream;
  for (const Envelope& message : messages) {
    auto frame = encodeFrame(message);
    EXPECT_TRUE(frame.isOk()) << frame.status().toString();
    if (frame.isOk()) stream += *frame;
  }
  return stream;
}

// Feeds `stream` in the chunks that start at each offset of `cuts`, draining
// the decoder after every chunk as a network loop would.
template <typename Envelope>
std::vector<Envelope> decodeChunks(const std::string& stream, const std::vector<size_t>& cuts) {
  FrameDecoder decoder;
  std::vector<Envelope> out;
  for (size_t i = 0; i < cuts.size(); ++i) {
    const size_t end = i + 1 < cuts.size() ? cuts[i + 1] : stream.size();
    EXPECT_TRUE(decoder.feed(std::string_view(stream).substr(cuts[i], end - cuts[i])).isOk());
    Envelope message;
    while (true) {
      auto got = decoder.next(message);
      EXPECT_TRUE(got.isOk()) << got.status().toString();
      if (!got.isOk() || !*got) break;
      out.push_back(message);
    }
  }
  EXPECT_TRUE(decoder.finish().isOk()) << decoder.status().toString();
  EXPECT_EQ(decoder.bufferedBytes(), 0u);
  return out;
}

template <typename Envelope>
void expectSameMessages(const std::vector<Envelope>& expected, const std::vector<Envelope>& actual,
                        const std::string& how) {
  ASSERT_EQ(expected.size(), actual.size()) << how;
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(MessageDifferencer::Equals(expected[i], actual[i]))
        << how << ", message " << i << ":\nexpected " << expected[i].DebugString() << "\ngot "
        << actual[i].DebugString();
  }
}

template <typename Envelope>
void roundTripEachMessage(const std::vector<Envelope>& samples) {
  for (const Envelope& sample : samples) {
    auto frame = encodeFrame(sample);
    ASSERT_TRUE(frame.isOk()) << frame.status().toString();
    const std::string& bytes = *frame;
    ASSERT_EQ(bytes.size(), kFrameHeaderBytes + sample.ByteSizeLong());
    const std::vector<Envelope> expected = {sample};
    expectSameMessages(expected, decodeChunks<Envelope>(bytes, {0}), "whole");
    for (size_t cut = 1; cut < bytes.size(); ++cut) {
      expectSameMessages(expected, decodeChunks<Envelope>(bytes, {0, cut}),
                         "split at byte " + std::to_string(cut));
    }
    std::vector<size_t> everyByte(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i) everyByte[i] = i;
    expectSameMessages(expected, decodeChunks<Envelope>(bytes, everyByte), "one byte at a time");
  }
}

TEST(ProtocolFraming, EveryClientMessageRoundTripsAtEverySplit) {
  roundTripEachMessage(testing::sampleClientMessages());
}

TEST(ProtocolFraming, EveryServerMessageRoundTripsAtEverySplit) {
  roundTripEachMessage(testing::sampleServerMessages());
}

// Frame boundaries inside a chunk, and chunks ending inside prefixes.
TEST(ProtocolFraming, AStreamOfAllMessagesDecodesAtEverySplit) {
  const auto samples = testing::sampleClientMessages();
  const std::string stream = encodeAll(samples);
  for (size_t cut = 0; cut < stream.size(); ++cut) {
    expectSameMessages(samples, decodeChunks<wire::ClientMessage>(stream, {0, cut}),
                       "stream split at byte " + std::to_string(cut));
  }
  std::vector<size_t> everyByte(stream.size());
  for (size_t i = 0; i < stream.size(); ++i) everyByte[i] = i;
  expectSameMessages(samples, decodeChunks<wire::ClientMessage>(stream, everyByte),
                     "stream one byte at a time");
}

TEST(ProtocolFraming, PrefixIsBigEndianPayloadLength) {
  wire::ClientMessage message;
  message.set_client_seq(1);
  message.mutable_create_document()->set_mesh(std::string(300, 'x'));
  auto frame = encodeFrame(message);
  ASSERT_TRUE(frame.isOk());
  const size_t length = message.ByteSizeLong();
  ASSERT_GT(length, 255u);
  EXPECT_EQ(static_cast<unsigned char>((*frame)[0]), 0);
  EXPECT_EQ(static_cast<unsigned char>((*frame)[1]), 0);
  EXPECT_EQ(static_cast<unsigned char>((*frame)[2]), length >> 8);
  EXPECT_EQ(static_cast<unsigned char>((*frame)[3]), length & 0xff);
  EXPECT_EQ(frame->substr(kFrameHeaderBytes), message.SerializeAsString());
}

TEST(ProtocolFraming, EncodeRefusesAnEmptyEnvelope) {
  auto frame = encodeFrame(wire::ClientMessage());
  ASSERT_FALSE(frame.isOk());
  EXPECT_EQ(frame.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(frame.status().message().find("empty tessera.wire.ClientMessage"), std::string::npos)
      << frame.status().message();
}

TEST(ProtocolFraming, EncodeRefusesAMessageOverTheLimit) {
  wire::ServerMessage message;
  message.mutable_export_result()->set_glb(std::string(1000, 'g'));
  auto frame = encodeFrame(message, 512);
  ASSERT_FALSE(frame.isOk());
  EXPECT_NE(frame.status().message().find("exceeds the frame limit of 512 bytes"), std::string::npos)
      << frame.status().message();
  EXPECT_TRUE(encodeFrame(message, static_cast<uint32_t>(message.ByteSizeLong())).isOk());
}

// A newer peer's fields survive as unknown fields: the decoder does not drop
// a frame because it carries something this build does not know.
TEST(ProtocolFraming, UnknownFieldsFromANewerPeerAreKept) {
  wire::ClientMessage message;
  message.set_client_seq(3);
  message.mutable_ping();
  std::string payload = message.SerializeAsString();
  payload += std::string("\xa0\x06\x07", 3);  // field 100, varint 7
  const uint32_t n = static_cast<uint32_t>(payload.size());
  std::string frame = {0, 0, 0, static_cast<char>(n)};
  frame += payload;

  FrameDecoder decoder;
  ASSERT_TRUE(decoder.feed(frame).isOk());
  wire::ClientMessage decoded;
  auto got = decoder.next(decoded);
  ASSERT_TRUE(got.isOk() && *got) << got.status().toString();
  EXPECT_TRUE(decoded.has_ping());
  EXPECT_EQ(decoded.client_seq(), 3u);
  EXPECT_EQ(decoded.SerializeAsString(), payload);
}

}  // namespace
}  // namespace tessera
