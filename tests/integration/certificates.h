// Self-signed certificates for TLS tests, made with Debian's openssl tool.
#pragma once

#include <cstdlib>
#include <string>

namespace tessera::testing {

// DIR/NAME.pem and DIR/NAME.key: a certificate for 127.0.0.1, valid a day.
inline bool makeCertificate(const std::string& dir, const std::string& name) {
  const std::string command =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=127.0.0.1 "
      "-addext subjectAltName=IP:127.0.0.1 -keyout " +
      dir + "/" + name + ".key -out " + dir + "/" + name + ".pem >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

}  // namespace tessera::testing
