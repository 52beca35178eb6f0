#include "server/cluster/nats_blobs.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "core/util/byte_io.h"
#include "core/util/fnv1a.h"

namespace tessera::cluster {

namespace {

constexpr std::string_view kManifestMagic = "TB1";

Status publish(NatsLink& link, const std::string& subject, std::string_view bytes) {
  jsPubAck* ack = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  const natsStatus s = js_Publish(&ack, link.jetStream(), subject.c_str(), bytes.data(),
                                  static_cast<int>(bytes.size()), nullptr, &code);
  PubAckPtr owned(ack);
  if (s != NATS_OK) return link.error(s, "writing " + subject, code);
  return Status::ok();
}

}  // namespace

Status putBlob(NatsLink& link, const std::string& stream, const std::string& prefix, std::string_view bytes) {
  (void)stream;  // the subject alone routes the message; kept for symmetry with getBlob
  // Within the NATS servers' max_payload, whatever it is set to.
  const int64_t maxPayload = natsConnection_GetMaxPayload(link.connection());
  const size_t chunkBytes = maxPayload > 8192
                                ? std::min<size_t>(kBlobChunkBytes, static_cast<size_t>(maxPayload) - 4096)
                                : kBlobChunkBytes;
  uint64_t chunks = 0;
  for (size_t at = 0; at < bytes.size() || chunks == 0; at += chunkBytes) {
    TESSERA_RETURN_IF_ERROR(
        publish(link, prefix + "." + std::to_string(chunks), bytes.substr(at, chunkBytes)));
    ++chunks;
    if (bytes.empty()) break;
  }
  ByteWriter manifest;
  manifest.putBytes(kManifestMagic);
  manifest.put<uint64_t>(bytes.size());
  manifest.put<uint64_t>(chunks);
  manifest.put<uint64_t>(fnv1a64(bytes));
  return publish(link, prefix, manifest.bytes());
}

Expected<std::string> getBlob(NatsLink& link, const std::string& stream, const std::string& prefix,
                              std::string_view where) {
  TESSERA_ASSIGN_OR_RETURN(LastMessage manifest, lastMessage(link, stream, prefix));
  const std::string& m = manifest.payload;
  if (m.size() != kManifestMagic.size() + 24 || m.compare(0, kManifestMagic.size(), kManifestMagic) != 0) {
    return parseError(std::string(where) + ": its manifest on " + prefix + " is damaged (" +
                      std::to_string(m.size()) + " bytes)");
  }
  ByteReader in(m.data() + kManifestMagic.size(), m.size() - kManifestMagic.size(), std::string(where));
  uint64_t size = 0, chunks = 0, checksum = 0;
  TESSERA_RETURN_IF_ERROR(in.get(size, "the manifest's size"));
  TESSERA_RETURN_IF_ERROR(in.get(chunks, "the manifest's chunk count"));
  TESSERA_RETURN_IF_ERROR(in.get(checksum, "the manifest's checksum"));
  if (chunks == 0 || chunks > size + 1) {
    return parseError(std::string(where) + ": its manifest names " + std::to_string(chunks) + " chunks for " +
                      std::to_string(size) + " bytes");
  }
  std::string bytes;
  bytes.reserve(size);
  for (uint64_t i = 0; i < chunks; ++i) {
    auto chunk = lastMessage(link, stream, prefix + "." + std::to_string(i));
    if (!chunk.isOk()) {
      return parseError(std::string(where) + ": chunk " + std::to_string(i) + " of " +
                        std::to_string(chunks) + " is missing (" + chunk.status().message() + ")");
    }
    bytes += chunk->payload;
  }
  if (bytes.size() != size || fnv1a64(bytes) != checksum) {
    return parseError(std::string(where) + ": its chunks hold " + std::to_string(bytes.size()) +
                      " bytes that do not match the manifest (" + std::to_string(size) +
                      " bytes and its checksum)");
  }
  return bytes;
}

Expected<LastMessage> lastMessage(NatsLink& link, const std::string& stream, const std::string& subject) {
  natsMsg* raw = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  const natsStatus s = js_GetLastMsg(&raw, link.jetStream(), stream.c_str(), subject.c_str(), nullptr, &code);
  NatsMsgPtr msg(raw);
  if (s == NATS_NOT_FOUND) return notFound("no message on " + subject);
  if (s != NATS_OK) return link.error(s, "reading " + subject, code);
  LastMessage last;
  last.payload.assign(natsMsg_GetData(msg.get()), static_cast<size_t>(natsMsg_GetDataLength(msg.get())));
  last.sequence = natsMsg_GetSequence(msg.get());
  return last;
}

Expected<LastMessage> nextMessage(NatsLink& link, const std::string& stream, const std::string& subject,
                                  uint64_t from) {
  jsDirectGetMsgOptions options;
  jsDirectGetMsgOptions_Init(&options);
  options.Sequence = from;
  options.NextBySubject = subject.c_str();
  natsMsg* raw = nullptr;
  const natsStatus s = js_DirectGetMsg(&raw, link.jetStream(), stream.c_str(), nullptr, &options);
  NatsMsgPtr msg(raw);
  if (s == NATS_NOT_FOUND)
    return notFound("no message on " + subject + " from stream sequence " + std::to_string(from));
  if (s != NATS_OK)
    return link.error(s, "reading " + subject + " from stream sequence " + std::to_string(from));
  LastMessage next;
  next.payload.assign(natsMsg_GetData(msg.get()), static_cast<size_t>(natsMsg_GetDataLength(msg.get())));
  next.sequence = natsMsg_GetSequence(msg.get());
  if (next.sequence == 0) {
    // Direct gets carry the sequence in a header.
    const char* header = nullptr;
    if (natsMsgHeader_Get(msg.get(), "Nats-Sequence", &header) == NATS_OK && header != nullptr) {
      next.sequence = std::strtoull(header, nullptr, 10);
    }
  }
  if (next.sequence < from)
    return link.error(NATS_ERR, "reading " + subject + ": a direct get without its sequence");
  return next;
}

Expected<LastMessage> nextMessageOnReplicas(NatsLink& link, const std::string& stream,
                                            const std::string& subject, uint64_t from) {
  for (int lagging = 0;; ++lagging) {
    auto next = nextMessage(link, stream, subject, from);
    if (next.isOk() || next.status().code() != ErrorCode::kNotFound || lagging >= 50) return next;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

Status deleteMessagesOn(NatsLink& link, const std::string& stream, const std::string& subject) {
  uint64_t from = 1;
  for (;;) {
    auto next = nextMessage(link, stream, subject, from);
    if (!next.isOk()) return next.status().code() == ErrorCode::kNotFound ? Status::ok() : next.status();
    jsErrCode code = static_cast<jsErrCode>(0);
    const natsStatus s = js_DeleteMsg(link.jetStream(), stream.c_str(), next->sequence, nullptr, &code);
    // NATS_NOT_FOUND: deleted meanwhile by another node.
    if (s != NATS_OK && s != NATS_NOT_FOUND)
      return link.error(s, "deleting stream sequence " + std::to_string(next->sequence) + " of " + subject,
                        code);
    from = next->sequence + 1;
  }
}

}  // namespace tessera::cluster
