#include "client/lib/session.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/write.hpp>
#include <thread>

#include "protocol/handshake.h"

namespace tessera::client {

namespace asio = boost::asio;
using asio::ip::tcp;

const std::string kReceiveTimeout = "no message from the server within ";

bool isReceiveTimeout(const Status& status) {
  return status.code() == ErrorCode::kTimeout;
}

Session::Session(const SessionOptions& options)
    : options_(options), socket_(io_), decoder_(FrameDecoderOptions{options.maxFrameBytes}) {}

Expected<std::unique_ptr<Session>> Session::connect(const SessionOptions& options) {
  return connect(options, nullptr);
}

Expected<std::unique_ptr<Session>> Session::connect(const SessionOptions& options, wire::ErrorCode* refusal) {
  std::unique_ptr<Session> s(new Session(options));
  boost::system::error_code ec;
  tcp::resolver resolver(s->io_);
  auto endpoints = resolver.resolve(options.host, std::to_string(options.port), ec);
  if (ec) return ioError("cannot resolve " + options.host + ": " + ec.message());
  if (options.receiveBufferBytes > 0 || !options.localAddress.empty()) {
    // Before connecting, so the TCP window is negotiated with it.
    s->socket_.open(endpoints.begin()->endpoint().protocol(), ec);
    if (!ec && options.receiveBufferBytes > 0) {
      s->socket_.set_option(asio::socket_base::receive_buffer_size(options.receiveBufferBytes), ec);
    }
    if (!ec && !options.localAddress.empty()) {
      const auto local = asio::ip::make_address(options.localAddress, ec);
      if (!ec) s->socket_.bind(tcp::endpoint(local, 0), ec);
    }
    if (!ec) s->socket_.connect(endpoints.begin()->endpoint(), ec);
  } else {
    asio::connect(s->socket_, endpoints, ec);
  }
  if (ec)
    return ioError("cannot connect to " + options.host + ":" + std::to_string(options.port) + ": " +
                   ec.message());
  s->socket_.set_option(tcp::no_delay(true), ec);
  if (options.tls) {
    s->tlsContext_ = std::make_unique<asio::ssl::context>(asio::ssl::context::tls_client);
    if (options.tlsCaFile.empty()) {
      s->tlsContext_->set_default_verify_paths(ec);
    } else {
      s->tlsContext_->load_verify_file(options.tlsCaFile, ec);
    }
    if (ec) return invalidArgument("TLS: cannot load trusted certificates: " + ec.message());
    s->tls_.emplace(s->socket_, *s->tlsContext_);
    s->tls_->set_verify_mode(asio::ssl::verify_peer);
    s->tls_->set_verify_callback(asio::ssl::host_name_verification(options.host));
    s->tls_->handshake(asio::ssl::stream_base::client, ec);
    if (ec) return ioError("TLS handshake with " + options.host + " failed: " + ec.message());
  }
  HelloOptions hello;
  hello.clientSeq = s->nextSeq_++;
  hello.clientName = options.name;
  hello.token = options.token;
  TESSERA_ASSIGN_OR_RETURN(uint64_t seq, s->send(makeHello(hello)));
  (void)seq;
  TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage first, s->readMessage(options.timeoutSeconds));
  if (first.has_error() && refusal != nullptr) *refusal = first.error().code();
  TESSERA_RETURN_IF_ERROR(checkHelloAck(first));
  s->sessionId_ = first.hello_ack().session_id();
  s->role_ = first.hello_ack().role();
  return s;
}

Expected<std::unique_ptr<Session>> Session::connectWithBackoff(const SessionOptions& options, int attempts,
                                                               double firstDelaySeconds) {
  double delay = firstDelaySeconds;
  Status last = ioError("no connection attempt was made");
  for (int i = 0; i < attempts; ++i) {
    auto session = connect(options);
    if (session.isOk()) return session;
    last = session.status();
    if (i + 1 < attempts) {
      std::this_thread::sleep_for(std::chrono::duration<double>(delay));
      delay = std::min(delay * 2.0, 5.0);
    }
  }
  return Status(last.code(), last.message() + " (after " + std::to_string(attempts) + " attempts)");
}

Expected<uint64_t> Session::send(wire::ClientMessage message) {
  if (message.client_seq() == 0) message.set_client_seq(nextSeq_++);
  TESSERA_ASSIGN_OR_RETURN(std::string frame, encodeFrame(message, options_.maxFrameBytes));
  TESSERA_RETURN_IF_ERROR(sendRaw(frame));
  return message.client_seq();
}

Status Session::sendRaw(const std::string& bytes) {
  boost::system::error_code ec;
  if (tls_) {
    asio::write(*tls_, asio::buffer(bytes), ec);
  } else {
    asio::write(socket_, asio::buffer(bytes), ec);
  }
  if (ec) return ioError("send failed: " + ec.message());
  return Status::ok();
}

Expected<wire::ServerMessage> Session::readMessage(double timeoutSeconds) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(timeoutSeconds));
  for (;;) {
    wire::ServerMessage message;
    TESSERA_ASSIGN_OR_RETURN(bool got, decoder_.next(message));
    if (got) return message;
    // One read stays in flight across calls: a timeout leaves it pending
    // instead of cancelling it, because a cancelled read may already have
    // completed with bytes, and dropping them corrupts the stream.
    if (!read_.pending) startRead();
    io_.restart();
    io_.run_until(deadline);
    if (read_.pending) return timeoutError(kReceiveTimeout + std::to_string(timeoutSeconds) + " s");
    if (read_.result) return ioError("connection closed: " + read_.result.message());
    TESSERA_RETURN_IF_ERROR(decoder_.feed(std::string_view(buffer_.data(), read_.bytes)));
  }
}

void Session::startRead() {
  read_ = PendingRead{.pending = true};
  auto done = [this](const boost::system::error_code& ec, size_t bytes) {
    read_ = PendingRead{.pending = false, .result = ec, .bytes = bytes};
  };
  if (tls_) {
    tls_->async_read_some(asio::buffer(buffer_), done);
  } else {
    socket_.async_read_some(asio::buffer(buffer_), done);
  }
}

Expected<wire::ServerMessage> Session::receive(double timeoutSeconds) {
  if (!backlog_.empty()) {
    wire::ServerMessage m = std::move(backlog_.front());
    backlog_.pop_front();
    return m;
  }
  return readMessage(timeoutSeconds);
}

Expected<wire::ServerMessage> Session::call(wire::ClientMessage message, double timeoutSeconds) {
  TESSERA_ASSIGN_OR_RETURN(uint64_t seq, send(std::move(message)));
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(timeoutSeconds));
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0)
      return ioError("no reply to message " + std::to_string(seq) + " within " +
                     std::to_string(timeoutSeconds) + " s");
    TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage m, readMessage(left));
    if (replyTo(m) == seq) return m;
    if (m.has_error() && m.error().fatal()) return ioError("server error: " + m.error().message());
    backlog_.push_back(std::move(m));
  }
}

void Session::close() {
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

}  // namespace tessera::client
