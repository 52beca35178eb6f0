#include "server/cluster/message_chunks.h"

#include <algorithm>
#include <atomic>

#include "core/util/byte_io.h"

namespace tessera::cluster {

namespace {

constexpr size_t kChunkOverhead = 1 + 1 + 255 + 8 + 4 + 4;
std::atomic<uint64_t> nextMessageId{1};

}  // namespace

Status publishMessage(NatsLink& link, const std::string& subject, const std::string& sender,
                      std::string_view message) {
  const int64_t maxPayload = natsConnection_GetMaxPayload(link.connection());
  auto send = [&](const std::string& bytes) -> Status {
    const natsStatus s = natsConnection_Publish(link.connection(), subject.c_str(), bytes.data(),
                                                static_cast<int>(bytes.size()));
    if (s != NATS_OK)
      return link.error(s, "publishing " + std::to_string(bytes.size()) + " bytes on " + subject);
    return Status::ok();
  };
  if (maxPayload <= 0 || message.size() + 1 <= static_cast<size_t>(maxPayload)) {
    std::string whole(1, '\0');
    whole += message;
    return send(whole);
  }
  if (sender.size() > 255 || static_cast<size_t>(maxPayload) <= kChunkOverhead + 1024) {
    return invalidArgument("cannot chunk a message for " + subject + " (max_payload " +
                           std::to_string(maxPayload) + ")");
  }
  const size_t chunk = static_cast<size_t>(maxPayload) - kChunkOverhead;
  const uint64_t id = nextMessageId++;
  const uint32_t parts = static_cast<uint32_t>((message.size() + chunk - 1) / chunk);
  for (uint32_t part = 0; part < parts; ++part) {
    ByteWriter bytes;
    bytes.put<uint8_t>(1);
    bytes.put<uint8_t>(static_cast<uint8_t>(sender.size()));
    bytes.putBytes(sender);
    bytes.put<uint64_t>(id);
    bytes.put<uint32_t>(part);
    bytes.put<uint32_t>(parts);
    bytes.putBytes(message.substr(static_cast<size_t>(part) * chunk, chunk));
    TESSERA_RETURN_IF_ERROR(send(bytes.bytes()));
  }
  return Status::ok();
}

Expected<std::optional<std::string>> ChunkAssembler::add(std::string_view payload) {
  if (payload.empty()) return invalidArgument("an empty cluster message");
  if (payload[0] == '\0') return std::optional<std::string>(std::string(payload.substr(1)));
  if (payload[0] != '\1')
    return invalidArgument("not a cluster message (first byte " +
                           std::to_string(static_cast<unsigned char>(payload[0])) + ")");
  ByteReader in(payload.data() + 1, payload.size() - 1, "its bytes");
  uint8_t senderBytes = 0;
  std::string sender;
  uint64_t id = 0;
  uint32_t part = 0, parts = 0;
  Status header = in.get(senderBytes, "the sender's length");
  if (header.isOk()) header = in.getBytes(sender, senderBytes, "the sender");
  if (header.isOk()) header = in.get(id, "the message id");
  if (header.isOk()) header = in.get(part, "the part");
  if (header.isOk()) header = in.get(parts, "the part count");
  if (!header.isOk()) return invalidArgument("a cluster chunk without its header (" + header.message() + ")");
  const std::string_view data = payload.substr(1 + in.offset());
  std::lock_guard<std::mutex> lock(mutex_);
  Partial& p = partial_[sender];
  if (part == 0) {
    held_ -= p.bytes.size();
    p = Partial{id, 0, parts, {}, ++clock_};
  }
  if (p.id != id || p.next != part || p.parts != parts || parts == 0) {
    held_ -= p.bytes.size();
    partial_.erase(sender);
    return invalidArgument("cluster chunk " + std::to_string(part) + " of " + std::to_string(parts) +
                           " from " + sender + " out of order (message " + std::to_string(id) + ")");
  }
  p.bytes += data;
  held_ += data.size();
  ++p.next;
  if (p.next == p.parts) {
    std::string whole = std::move(p.bytes);
    held_ -= whole.size();
    partial_.erase(sender);
    return std::optional<std::string>(std::move(whole));
  }
  // Bounded: a sender that never finishes loses its oldest message first.
  while (held_ > maxPartialBytes_ && !partial_.empty()) {
    auto oldest = std::min_element(partial_.begin(), partial_.end(),
                                   [](const auto& a, const auto& b) { return a.second.age < b.second.age; });
    held_ -= oldest->second.bytes.size();
    partial_.erase(oldest);
  }
  return std::optional<std::string>();
}

}  // namespace tessera::cluster
