// What a Connection runs on: a byte stream (TCP, or TLS over TCP) on the
// protocol port, or a WebSocket (plain or TLS) on --ws-port (docs/PROTOCOL.md §1.2).
// The Connection speaks frames (protocol/framing.h) on every transport and
// does not know which one it has; the transport knows no frames, except
// that a WebSocket checks each message is exactly one (message_framing.h).
//
// Every operation is started from the Connection's strand, and its
// completion runs there: the transport binds it to the strand it was made
// with. At most one read and one write are in flight at a time.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/strand.hpp>
#include <boost/system/error_code.hpp>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/status.h"

namespace tessera::server {

using ConnectionStrand = boost::asio::strand<boost::asio::any_io_executor>;

class Transport {
 public:
  using Done = std::function<void(const boost::system::error_code&)>;
  // Bytes read; for a WebSocket, a Status that is not ok when the peer
  // broke the one-frame-per-message rule (the Connection answers it as a
  // malformed frame), and no bytes for a text message.
  using Read = std::function<void(const boost::system::error_code&, std::string_view bytes, Status framing)>;
  using Written = std::function<void(const boost::system::error_code&, size_t bytes)>;

  virtual ~Transport() = default;

  // Whether start() must run (and succeed) before frames are read or
  // written: TLS and WebSocket have handshakes, plain TCP has none.
  virtual bool needsHandshake() const = 0;
  // The transport's own handshake (TLS, the WebSocket accept).
  virtual void start(Done done) = 0;
  virtual void read(Read done) = 0;
  // Writes the frames in order; each stays alive until `done` runs.
  virtual void write(std::vector<std::shared_ptr<const std::string>> frames, Written done) = 0;
  // Closes at once; pending operations complete with an error.
  virtual void close() = 0;
  // For logs: "tcp", "tls", "ws" or "wss".
  virtual const char* kind() const = 0;
};

// The protocol port's transports: plain TCP, or TLS with `tls` set.
std::unique_ptr<Transport> makeStreamTransport(boost::asio::ip::tcp::socket socket,
                                               boost::asio::ssl::context* tls,
                                               const ConnectionStrand& strand);

}  // namespace tessera::server
