#include "server/cluster/journal_message.h"

namespace tessera::cluster {

namespace {

constexpr std::string_view kMagic = "TJ2";

void putLittleEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

uint64_t getLittleEndian(std::string_view in, size_t at, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= static_cast<uint64_t>(static_cast<unsigned char>(in[at + i])) << (8 * i);
  return value;
}

}  // namespace

std::string encodeJournalMessage(const JournalMessage& m) {
  std::string out;
  out.reserve(kMagic.size() + 29 + m.author.size() + m.bytes.size());
  out += kMagic;
  out.push_back(m.fence ? 1 : 0);
  putLittleEndian(out, m.version, 8);
  putLittleEndian(out, m.author.size(), 4);
  out += m.author;
  putLittleEndian(out, m.authorSession, 8);
  putLittleEndian(out, m.clientSeq, 8);
  out += m.bytes;
  return out;
}

Expected<JournalMessage> decodeJournalMessage(std::string_view payload, std::string_view where) {
  const size_t header = kMagic.size() + 13;
  if (payload.size() < header || payload.substr(0, kMagic.size()) != kMagic) {
    return parseError(std::string(where) + ": not a Tessera journal message (" + std::to_string(payload.size()) +
                      " bytes without the TJ2 header)");
  }
  JournalMessage message;
  const unsigned kind = static_cast<unsigned char>(payload[kMagic.size()]);
  if (kind > 1) return parseError(std::string(where) + ": unknown journal message kind " + std::to_string(kind));
  message.fence = kind == 1;
  message.version = getLittleEndian(payload, kMagic.size() + 1, 8);
  const uint64_t authorBytes = getLittleEndian(payload, kMagic.size() + 9, 4);
  if (authorBytes > payload.size() - header || payload.size() - header - authorBytes < 16) {
    return parseError(std::string(where) + ": its author length " + std::to_string(authorBytes) + " passes the end of its " +
                      std::to_string(payload.size()) + " bytes");
  }
  message.author = std::string(payload.substr(header, authorBytes));
  message.authorSession = getLittleEndian(payload, header + authorBytes, 8);
  message.clientSeq = getLittleEndian(payload, header + authorBytes + 8, 8);
  message.bytes = std::string(payload.substr(header + authorBytes + 16));
  return message;
}

}  // namespace tessera::cluster
