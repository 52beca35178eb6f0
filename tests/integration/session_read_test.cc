// Clients never lose bytes: a receive() whose timeout fires
// while its read completes must still hand the read's bytes to the decoder.
// A test server on loopback sends a multi-megabyte snapshot of a real mesh
// (fandisk's level-2 tessellation) in many small writes while the client
// polls with a one-millisecond timeout and two threads keep both cores
// busy; every snapshot must arrive byte for byte and decode to the surface
// the server encoded. Before the fix the stream broke within the first
// snapshot ("frame N announces ... bytes", or a region that did not decode).
#include <gtest/gtest.h>

#include <cstdio>

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "protocol/framing.h"
#include "protocol/handshake.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using Clock = std::chrono::steady_clock;

constexpr uint64_t kDocument = 7;

// fandisk's level-2 tessellation as one Snapshot message.
wire::ServerMessage fandiskSnapshot() {
  auto mesh = importMesh(testing::cgalMeshPath("fandisk.off"));
  EXPECT_TRUE(mesh.isOk()) << mesh.status().message();
  auto doc = Document::create(*mesh, DocumentOptions{.loop = {}, .maxLevel = 4});
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  // Deepest level 4: a region per base face (a coarser profile groups them
  // into a few hundred regions and megabytes no more).
  auto t = Tessellation::build(*doc, {.baseLevel = 2, .maxLevel = 4, .angleThresholdDegrees = 15});
  auto grid = documentGrid(*doc);
  EXPECT_TRUE(t.isOk() && grid.isOk());
  wire::ServerMessage m;
  m.mutable_snapshot()->set_document_id(kDocument);
  m.mutable_snapshot()->set_version(1);
  for (const auto& [id, region] : t->regions()) {
    RegionHeader header;
    header.regionId = id;
    header.documentVersion = 1;
    header.profile = t->profile();
    header.grid = *grid;
    auto bytes = encodeRegion(header, region);
    EXPECT_TRUE(bytes.isOk()) << bytes.status().message();
    wire::Region* r = m.mutable_snapshot()->add_regions();
    r->set_region_id(id);
    r->set_draco(*bytes);
  }
  return m;
}

// Keeps a core busy until destroyed.
class Spinner {
 public:
  Spinner()
      : thread_([this] {
          volatile uint64_t x = 0;
          while (!stop_) x = x + 1;
        }) {}
  ~Spinner() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Answers one Hello, then writes `frame` `copies` times in `chunk`-byte
// writes with a short pause every few chunks, so data keeps arriving while
// the client's polls time out.
void trickleServer(tcp::acceptor& acceptor, const std::string& frame, int copies, size_t chunk) {
  asio::io_context io;
  tcp::socket socket(io);
  acceptor.accept(socket);
  FrameDecoder decoder;
  wire::ClientMessage hello;
  std::array<char, 4096> buffer{};
  for (;;) {
    auto got = decoder.next(hello);
    if (!got.isOk() || *got) break;
    boost::system::error_code ec;
    const size_t n = socket.read_some(asio::buffer(buffer), ec);
    if (ec) return;
    if (!decoder.feed(std::string_view(buffer.data(), n)).isOk()) return;
  }
  HelloAckOptions ack;
  ack.clientSeq = hello.client_seq();
  ack.serverVersion = "trickle test server";
  ack.sessionId = 1;
  ack.role = wire::ROLE_VIEWER;
  auto ackFrame = encodeFrame(makeHelloAck(ack), 64u << 20);
  if (!ackFrame.isOk()) return;
  asio::write(socket, asio::buffer(*ackFrame));
  for (int c = 0; c < copies; ++c) {
    for (size_t at = 0, i = 0; at < frame.size(); at += chunk, ++i) {
      boost::system::error_code ec;
      asio::write(socket, asio::buffer(frame.data() + at, std::min(chunk, frame.size() - at)), ec);
      if (ec) return;
      if (i % 8 == 7) std::this_thread::sleep_for(std::chrono::microseconds(200));
      // A pause longer than the client's 1 ms poll now and then, so that
      // polls time out in the middle of a frame however fast or loaded the
      // machine is (on a loaded one, 200 us pauses alone gave fewer than 100).
      if (i % 64 == 63) std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
  }
  // Stay open until the client has read everything and closed.
  boost::system::error_code ec;
  socket.read_some(asio::buffer(buffer), ec);
}

TEST(SessionRead, AShortPollingTimeoutNeverLosesBytesUnderLoad) {
  const wire::ServerMessage snapshot = fandiskSnapshot();
  const std::string sent = snapshot.SerializeAsString();
  ASSERT_GT(sent.size(), 2u << 20) << "the snapshot should take megabytes";
  client::DocumentView direct(kDocument);
  ASSERT_TRUE(direct.apply(snapshot).isOk());
  auto frame = encodeFrame(snapshot, 64u << 20);
  ASSERT_TRUE(frame.isOk());

  asio::io_context io;
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  const uint16_t port = acceptor.local_endpoint().port();
  constexpr int kCopies = 4;
  std::thread server([&] { trickleServer(acceptor, *frame, kCopies, 1400); });

  Spinner a, b;  // both cores busy, as on the machine the viewer failed on
  auto session = client::Session::connect({.port = port, .name = "poller", .timeoutSeconds = 20});
  ASSERT_TRUE(session.isOk()) << session.status().message();
  int received = 0;
  uint64_t timeouts = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (received < kCopies && Clock::now() < deadline) {
    auto m = (*session)->receive(0.001);
    if (!m.isOk()) {
      ASSERT_TRUE(client::isReceiveTimeout(m.status()))
          << "copy " << received << ": " << m.status().message();
      ++timeouts;
      continue;
    }
    ASSERT_EQ(m->SerializeAsString(), sent) << "copy " << received << " differs from what the server sent";
    client::DocumentView view(kDocument);
    ASSERT_TRUE(view.apply(*m).isOk());
    EXPECT_EQ(view.surfaceHash(), direct.surfaceHash());
    ++received;
  }
  EXPECT_EQ(received, kCopies) << "only " << received << " snapshots within the deadline";
  // The point of the test is polls that time out while data arrives.
  std::printf("%llu polls timed out during the transfer\n", static_cast<unsigned long long>(timeouts));
  EXPECT_GT(timeouts, 100u);
  (*session)->close();
  server.join();
}

}  // namespace
}  // namespace tessera
