// A view-dependent subscriber against the real server (docs/VIEWS.md "The
// server"): its session, the surface it assembled from tiles, what came and
// how many bytes; and the checks every view test makes of it -- the
// server's surface hash, and no gap once the cracks between tiles of
// different levels are closed.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "client/lib/view_wire.h"
#include "core/document/document.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/cameras.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera::testing {

struct Model {
  Vec3 centre;
  double radius = 0;
};

// The bounding sphere of a model's points.
inline Model modelOf(std::span<const Vec3> points) {
  Vec3 lo = points[0], hi = lo;
  for (const Vec3& p : points) lo = testing::min(lo, p), hi = testing::max(hi, p);
  return {0.5 * (lo + hi), 0.5 * (hi - lo).norm()};
}

inline Model modelOf(const Document& doc) {
  return modelOf(doc.basePoints());
}

inline View lookAt(const Model& m, const Vec3& eye, const Vec3& target, int width, int height) {
  return testing::lookAt(eye, target, width, height, m.radius * 1e-3);
}

inline View randomView(const Model& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Vec3 dir(unit(rng), unit(rng), unit(rng));
  while (dir.norm() < 0.1) dir = Vec3(unit(rng), unit(rng), unit(rng));
  const double distance = m.radius * (0.8 + 3 * std::abs(unit(rng)));
  return lookAt(m, m.centre + distance * dir.normalized(),
                m.centre + 0.4 * m.radius * Vec3(unit(rng), unit(rng), unit(rng)), 390, 844);
}

// A viewer: its session and what it assembled.
struct Viewer {
  std::unique_ptr<client::Session> session;
  std::unique_ptr<client::DocumentView> view;
  std::set<uint64_t> received;  // every region id that came, over the run
  // The bytes of the picture held now: what sending it afresh would take.
  int64_t pictureBytes() const {
    int64_t sum = 0;
    for (const auto& [id, mesh] : view->regions()) sum += payloadBytes.at(id);
    return sum;
  }
  std::map<uint64_t, int64_t> payloadBytes;  // region id -> its latest payload's bytes
  int64_t payloads = 0, bytes = 0;
  std::vector<wire::Delta> deltas;  // as they came since the last clear
  // The first picture: the snapshot's regions and their bytes.
  std::vector<uint64_t> snapshotIds;
  int64_t snapshotBytes = 0;

  // Applies messages until the view is complete (a delta says so), after
  // `atLeast` deltas.
  Status untilComplete(double seconds = 60) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
      if (left <= 0)
        return timeoutError("the view was not complete within " + std::to_string(seconds) + " s");
      TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage m, session->receive(left));
      if (m.has_reject() || m.has_error()) return invalidArgument("refused: " + m.DebugString());
      TESSERA_RETURN_IF_ERROR(view->apply(m));
      const auto* regions = m.has_snapshot() ? &m.snapshot().regions()
                            : m.has_delta()  ? &m.delta().regions()
                                             : nullptr;
      if (m.has_snapshot()) {
        for (const wire::Region& r : m.snapshot().regions()) {
          snapshotIds.push_back(r.region_id());
          snapshotBytes += static_cast<int64_t>(r.draco().size());
        }
      }
      if (regions) {
        for (const wire::Region& r : *regions) {
          received.insert(r.region_id());
          payloadBytes[r.region_id()] = static_cast<int64_t>(r.draco().size());
          ++payloads;
          bytes += static_cast<int64_t>(r.draco().size());
        }
      }
      if (m.has_delta()) {
        deltas.push_back(m.delta());
        if (view->viewComplete()) return Status::ok();
      }
    }
  }
};

inline Expected<Viewer> subscribeViewer(const ServerProcess& server, uint64_t doc, const View& camera,
                                        const std::string& name) {
  Viewer v;
  TESSERA_ASSIGN_OR_RETURN(v.session, client::Session::connect(server.session(name, server.adminToken())));
  auto opened = v.session->call(testing::openDocument(doc), 30);
  if (!opened.isOk() || !opened->has_ack()) return ioError(name + ": cannot open the document");
  v.view = std::make_unique<client::DocumentView>(doc);
  auto subscribed = v.session->call(client::subscribeWithView(doc, camera), 60);
  if (!subscribed.isOk()) return subscribed.status();
  if (!subscribed->has_ack())
    return invalidArgument(name + ": subscribe refused: " + subscribed->DebugString());
  TESSERA_RETURN_IF_ERROR(v.untilComplete());
  return v;
}

// The viewer's assembled surface: its hash is the server's, and its tiles,
// cracks closed, leave no gap.
inline void expectWatertight(const Viewer& v, const Model& m, const std::string& where) {
  EXPECT_TRUE(v.view->verifySurface().isOk()) << where << ": " << v.view->verifySurface().message();
  std::vector<const RegionMesh*> meshes;
  std::vector<std::vector<Vec3>> closed;
  for (auto& [id, positions] : v.view->closedTilePositions()) {
    meshes.push_back(&v.view->regions().at(id));
    closed.push_back(std::move(positions));
  }
  EXPECT_EQ(testing::unmatchedEdges(meshes, closed, m.radius), 0)
      << where << ", " << meshes.size() << " tiles";
}

}  // namespace tessera::testing
