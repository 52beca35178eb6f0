// The morph side of a document host (docs/PROTOCOL.md §14): the views at a
// time t and the coarse stream of control points (the second key itself is
// added by morph_key_command.cc).
#include <algorithm>
#include <chrono>

#include "core/loop/level_builder.h"
#include "protocol/framing.h"
#include "server/base/log.h"
#include "server/document/document_host.h"
#include "server/document/replies.h"

namespace tessera::server {

Expected<DocumentHost::View> DocumentHost::buildMorphView(double t, const LodProfile& profile) {
  View view;
  view.morphT = t;
  TESSERA_ASSIGN_OR_RETURN(Document at, doc_.at(t));
  view.source = std::make_unique<Document>(std::move(at));
  TESSERA_ASSIGN_OR_RETURN(Tessellation tessellation, Tessellation::build(*view.source, profile));
  view.tessellation = std::make_unique<Tessellation>(std::move(tessellation));
  return view;
}

// A morph moves every region, so the view is built afresh; the regions
// whose surface hash (PROTOCOL 6.5) is unchanged are not sent again.
Expected<Tessellation::Changes> DocumentHost::rebuildMorphView(View& view) {
  TESSERA_ASSIGN_OR_RETURN(View fresh, buildMorphView(*view.morphT, view.tessellation->profile()));
  const std::map<uint64_t, uint64_t> before = std::move(view.regionHashes);
  view.tessellation = std::move(fresh.tessellation);
  view.source = std::move(fresh.source);
  view.regionHashes.clear();
  view.surfaceHash = 0;
  Tessellation::Changes changes;
  for (const auto& [region, mesh] : view.tessellation->regions()) {
    rehashRegion(view, region, grid_);
    auto old = before.find(region);
    if (old == before.end() || old->second != view.regionHashes[region]) changes.changed.push_back(region);
  }
  for (const auto& [region, hash] : before) {
    if (!view.tessellation->regions().count(region)) changes.removed.push_back(region);
  }
  // Ids always inline: the rebuilt regions have no earlier layout to refer to.
  changes.relaid = changes.changed;
  changes.rebuilt = true;
  // rehashRegion above counted the new regions; flush() rehashes the changed
  // ones again, which leaves the same sums.
  return changes;
}

void DocumentHost::morphControl(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                                wire::GetMorphControl request) {
  queue_.post(Lane::kInteractive, [self = shared_from_this(), who, clientSeq, request] {
    const uint32_t maxFrame = self->config_.limits.maxFrameBytes;
    const double t = request.t();
    auto points = self->doc_.pointsAt(t);
    if (!points.isOk()) {
      who->send({frameOf(rejectFor(clientSeq, points.status().withContext("morph control of document " +
                                                                          std::to_string(self->id_.value))),
                         maxFrame),
                 nullptr});
      return;
    }
    wire::ServerMessage m;
    wire::MorphControl* c = m.mutable_morph_control();
    c->set_client_seq(clientSeq);
    c->set_document_id(self->id_.value);
    c->set_version(self->version_);
    c->set_t(t);
    c->mutable_points()->Reserve(static_cast<int>(3 * points->size()));
    for (const Vec3& p : *points) {
      for (int k = 0; k < 3; ++k) c->add_points(static_cast<float>(p[k]));
    }
    if (request.with_topology()) {
      auto at = self->doc_.at(t);
      if (!at.isOk()) {
        who->send({frameOf(rejectFor(clientSeq, at.status()), maxFrame), nullptr});
        return;
      }
      const BaseTopology& base = at->baseTopology();
      for (const auto& tri : base.triangles) {
        for (int k = 0; k < 3; ++k) c->add_triangles(static_cast<uint32_t>(tri[k]));
      }
      for (const auto& crease : base.creases) {
        c->add_crease_vertices(static_cast<uint32_t>(crease.v0));
        c->add_crease_vertices(static_cast<uint32_t>(crease.v1));
        c->add_crease_sharpness(crease.sharpness);
      }
      for (float s : base.vertexSharpness) c->add_vertex_sharpness(s);
      const DocumentOptions& options = at->options();
      c->set_crease_method(options.loop.creaseMethod == CreaseMethod::kChaikin ? wire::CREASE_METHOD_CHAIKIN
                                                                               : wire::CREASE_METHOD_UNIFORM);
      c->set_boundary(options.loop.boundary == BoundaryInterpolation::kEdgeAndCorner
                          ? wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER
                          : wire::BOUNDARY_INTERPOLATION_EDGE_ONLY);
      c->set_max_level(static_cast<uint32_t>(options.maxLevel));
      c->set_image_from(self->doc_.images().from);
      c->set_image_to(self->doc_.images().to);
    }
    auto frame = frameOf(m, maxFrame);
    if (!frame) {
      who->send({frameOf(rejectFor(clientSeq, invalidArgument("the morph control exceeds the frame limit")),
                         maxFrame),
                 nullptr});
      return;
    }
    who->send({frame, nullptr});
  });
}

}  // namespace tessera::server
