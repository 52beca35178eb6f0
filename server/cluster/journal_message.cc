#include "server/cluster/journal_message.h"

namespace tessera::cluster {

namespace {

constexpr std::string_view kMagic = "TJ1";

void putLittleEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

uint64_t getLittleEndian(std::string_view in, size_t at, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= static_cast<uint64_t>(static_cast<unsigned char>(in[at + i])) << (8 * i);
  return value;
}

}  // namespace

std::string encodeJournalMessage(uint64_t version, std::string_view author, std::string_view bytes) {
  std::string out;
  out.reserve(kMagic.size() + 12 + author.size() + bytes.size());
  out += kMagic;
  putLittleEndian(out, version, 8);
  putLittleEndian(out, author.size(), 4);
  out += author;
  out += bytes;
  return out;
}

Expected<JournalMessage> decodeJournalMessage(std::string_view payload, std::string_view where) {
  const size_t header = kMagic.size() + 12;
  if (payload.size() < header || payload.substr(0, kMagic.size()) != kMagic) {
    return parseError(std::string(where) + ": not a Tessera journal message (" + std::to_string(payload.size()) +
                      " bytes without the TJ1 header)");
  }
  JournalMessage message;
  message.version = getLittleEndian(payload, kMagic.size(), 8);
  const uint64_t authorBytes = getLittleEndian(payload, kMagic.size() + 8, 4);
  if (authorBytes > payload.size() - header) {
    return parseError(std::string(where) + ": its author length " + std::to_string(authorBytes) + " passes the end of its " +
                      std::to_string(payload.size()) + " bytes");
  }
  message.author = std::string(payload.substr(header, authorBytes));
  message.bytes = std::string(payload.substr(header + authorBytes));
  return message;
}

}  // namespace tessera::cluster
