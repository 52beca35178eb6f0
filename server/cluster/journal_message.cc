#include "server/cluster/journal_message.h"

#include "core/util/byte_io.h"

namespace tessera::cluster {

namespace {

constexpr std::string_view kMagic = "TJ2";

}  // namespace

std::string encodeJournalMessage(const JournalMessage& m) {
  ByteWriter out;
  out.bytes().reserve(kMagic.size() + 29 + m.author.size() + m.bytes.size());
  out.putBytes(kMagic);
  out.put<uint8_t>(m.fence ? 1 : 0);
  out.put<uint64_t>(m.version);
  out.put<uint32_t>(static_cast<uint32_t>(m.author.size()));
  out.putBytes(m.author);
  out.put<uint64_t>(m.authorSession);
  out.put<uint64_t>(m.clientSeq);
  out.putBytes(m.bytes);
  return std::move(out.bytes());
}

Expected<JournalMessage> decodeJournalMessage(std::string_view payload, std::string_view where) {
  if (payload.substr(0, kMagic.size()) != kMagic) {
    return parseError(std::string(where) + ": not a Tessera journal message (" +
                      std::to_string(payload.size()) + " bytes without the TJ2 header)");
  }
  ByteReader in(payload.data() + kMagic.size(), payload.size() - kMagic.size(), std::string(where));
  JournalMessage message;
  uint8_t kind = 0;
  uint32_t authorBytes = 0;
  TESSERA_RETURN_IF_ERROR(in.get(kind, "the message kind"));
  if (kind > 1)
    return parseError(std::string(where) + ": unknown journal message kind " + std::to_string(kind));
  message.fence = kind == 1;
  TESSERA_RETURN_IF_ERROR(in.get(message.version, "the version"));
  TESSERA_RETURN_IF_ERROR(in.getCount(authorBytes, 1, "the author length"));
  TESSERA_RETURN_IF_ERROR(in.getBytes(message.author, authorBytes, "the author"));
  TESSERA_RETURN_IF_ERROR(in.get(message.authorSession, "the author's session"));
  TESSERA_RETURN_IF_ERROR(in.get(message.clientSeq, "the client sequence number"));
  TESSERA_RETURN_IF_ERROR(in.getBytes(message.bytes, in.remaining(), "the entry"));
  return message;
}

}  // namespace tessera::cluster
