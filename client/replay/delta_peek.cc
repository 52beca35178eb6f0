#include "client/replay/delta_peek.h"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/wire_format_lite.h>

#include "protocol/tessera.pb.h"

namespace tessera::replay {

namespace {

using google::protobuf::internal::WireFormatLite;

constexpr uint32_t tagOf(int field, WireFormatLite::WireType type) {
  return (static_cast<uint32_t>(field) << 3) | static_cast<uint32_t>(type);
}

}  // namespace

std::optional<DeltaHeader> peekDelta(std::string_view payload) {
  google::protobuf::io::CodedInputStream in(reinterpret_cast<const uint8_t*>(payload.data()),
                                            static_cast<int>(payload.size()));
  // The envelope holds exactly one field: its oneof body (tessera.proto).
  if (in.ReadTag() !=
      tagOf(wire::ServerMessage::kDeltaFieldNumber, WireFormatLite::WIRETYPE_LENGTH_DELIMITED)) {
    return std::nullopt;
  }
  uint32_t length = 0;
  if (!in.ReadVarint32(&length)) return std::nullopt;
  const auto limit = in.PushLimit(static_cast<int>(length));
  DeltaHeader h;
  for (uint32_t tag; (tag = in.ReadTag()) != 0;) {
    uint64_t* into = nullptr;
    switch (WireFormatLite::GetTagFieldNumber(tag)) {
      case wire::Delta::kDocumentIdFieldNumber:
        into = &h.documentId;
        break;
      case wire::Delta::kFromVersionFieldNumber:
        into = &h.fromVersion;
        break;
      case wire::Delta::kToVersionFieldNumber:
        into = &h.toVersion;
        break;
      case wire::Delta::kRegionsFieldNumber:
        ++h.regions;
        break;
      default:
        break;
    }
    if (into != nullptr && WireFormatLite::GetTagWireType(tag) == WireFormatLite::WIRETYPE_VARINT) {
      if (!in.ReadVarint64(into)) return std::nullopt;
    } else if (!WireFormatLite::SkipField(&in, tag)) {
      return std::nullopt;
    }
  }
  if (!in.ConsumedEntireMessage()) return std::nullopt;
  in.PopLimit(limit);
  if (in.ReadTag() != 0) return std::nullopt;  // something after the body: not a message we know
  return h;
}

}  // namespace tessera::replay
