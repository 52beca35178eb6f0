#include "server/document/morph_control.h"

#include <string>

#include "core/loop/level_builder.h"
#include "core/morph/morph.h"

namespace tessera::server {

Expected<wire::ServerMessage> morphControlMessage(const KeyedDocument& doc, uint64_t documentId,
                                                  uint64_t version, uint64_t clientSeq,
                                                  const wire::GetMorphControl& request) {
  TESSERA_RETURN_IF_ERROR(
      checkMorphScheme(doc.key0(), "morph control of document " + std::to_string(documentId)));
  const double t = request.t();
  auto points = doc.pointsAt(t);
  if (!points.isOk())
    return points.status().withContext("morph control of document " + std::to_string(documentId));
  wire::ServerMessage m;
  wire::MorphControl* c = m.mutable_morph_control();
  c->set_client_seq(clientSeq);
  c->set_document_id(documentId);
  c->set_version(version);
  c->set_t(t);
  c->mutable_points()->Reserve(static_cast<int>(3 * points->size()));
  for (const Vec3& p : *points) {
    for (int k = 0; k < 3; ++k) c->add_points(static_cast<float>(p[k]));
  }
  if (request.with_topology()) {
    TESSERA_ASSIGN_OR_RETURN(Document at, doc.at(t));
    const BaseTopology& base = at.baseTopology();
    for (const auto& tri : base.triangles) {
      for (int k = 0; k < 3; ++k) c->add_triangles(static_cast<uint32_t>(tri[k]));
    }
    for (const auto& crease : base.creases) {
      c->add_crease_vertices(static_cast<uint32_t>(crease.v0));
      c->add_crease_vertices(static_cast<uint32_t>(crease.v1));
      c->add_crease_sharpness(crease.sharpness);
    }
    for (float s : base.vertexSharpness) c->add_vertex_sharpness(s);
    const DocumentOptions& options = at.options();
    c->set_crease_method(options.loop.creaseMethod == CreaseMethod::kChaikin ? wire::CREASE_METHOD_CHAIKIN
                                                                             : wire::CREASE_METHOD_UNIFORM);
    c->set_boundary(options.loop.boundary == BoundaryInterpolation::kEdgeAndCorner
                        ? wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER
                        : wire::BOUNDARY_INTERPOLATION_EDGE_ONLY);
    c->set_max_level(static_cast<uint32_t>(options.maxLevel));
    c->set_image_from(doc.images().from);
    c->set_image_to(doc.images().to);
  }
  return m;
}

}  // namespace tessera::server
