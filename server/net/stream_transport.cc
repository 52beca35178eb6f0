// The protocol port's transports: frames as a byte stream over TCP, or over
// TLS (PROTOCOL.md §1).
#include <array>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl/stream.hpp>
#include <boost/asio/write.hpp>

#include "server/net/transport.h"

namespace tessera::server {

namespace asio = boost::asio;

namespace {

template <typename Stream>
class StreamTransport final : public Transport {
 public:
  template <typename... Args>
  StreamTransport(const ConnectionStrand& strand, bool tls, Args&&... args)
      : strand_(strand), tls_(tls), stream_(std::forward<Args>(args)...) {}

  bool needsHandshake() const override { return tls_; }

  void start(Done done) override {
    if constexpr (std::is_same_v<Stream, asio::ip::tcp::socket>) {
      asio::post(strand_, [done = std::move(done)] { done({}); });
    } else {
      stream_.async_handshake(asio::ssl::stream_base::server, asio::bind_executor(strand_, std::move(done)));
    }
  }

  void read(Read done) override {
    stream_.async_read_some(asio::buffer(buffer_),
                            asio::bind_executor(strand_, [this, done = std::move(done)](
                                                             const boost::system::error_code& ec, size_t n) {
                              done(ec, std::string_view(buffer_.data(), n), Status::ok());
                            }));
  }

  void write(std::vector<std::shared_ptr<const std::string>> frames, Written done) override {
    auto held = std::make_shared<std::vector<std::shared_ptr<const std::string>>>(std::move(frames));
    std::vector<asio::const_buffer> buffers;
    buffers.reserve(held->size());
    for (const auto& f : *held) buffers.push_back(asio::buffer(*f));
    asio::async_write(
        stream_, buffers,
        asio::bind_executor(strand_, [held, done = std::move(done)](const boost::system::error_code& ec,
                                                                    size_t n) { done(ec, n); }));
  }

  void close() override {
    boost::system::error_code ignored;
    socket().shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket().close(ignored);
  }

  const char* kind() const override { return tls_ ? "tls" : "tcp"; }

 private:
  asio::ip::tcp::socket& socket() {
    if constexpr (std::is_same_v<Stream, asio::ip::tcp::socket>) {
      return stream_;
    } else {
      return stream_.next_layer();
    }
  }

  ConnectionStrand strand_;
  bool tls_;
  Stream stream_;
  std::array<char, 64 * 1024> buffer_{};
};

}  // namespace

std::unique_ptr<Transport> makeStreamTransport(asio::ip::tcp::socket socket, asio::ssl::context* tls,
                                               const ConnectionStrand& strand) {
  if (tls != nullptr) {
    return std::make_unique<StreamTransport<asio::ssl::stream<asio::ip::tcp::socket>>>(
        strand, true, std::move(socket), *tls);
  }
  return std::make_unique<StreamTransport<asio::ip::tcp::socket>>(strand, false, std::move(socket));
}

}  // namespace tessera::server
