#include "server/store/token_hash.h"

#include <openssl/evp.h>

namespace tessera::store {

Expected<std::string> hashToken(std::string_view token) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int digestSize = 0;
  if (EVP_Digest(token.data(), token.size(), digest, &digestSize, EVP_sha256(), nullptr) != 1 ||
      digestSize != kTokenHashBytes) {
    return internalError("SHA-256 of an access token failed in OpenSSL");
  }
  return std::string(reinterpret_cast<const char*>(digest), digestSize);
}

}  // namespace tessera::store
