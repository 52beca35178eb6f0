#include "client/lib/view_wire.h"

#include <algorithm>

namespace tessera::client {

namespace {

void put(const Vec3& v, wire::Vec3* out) {
  out->set_x(v[0]);
  out->set_y(v[1]);
  out->set_z(v[2]);
}

}  // namespace

wire::View viewToWire(const View& view) {
  wire::View w;
  put(view.eye, w.mutable_eye());
  put(view.forward, w.mutable_forward());
  put(view.up, w.mutable_up());
  w.set_orthographic(view.projection == Projection::kOrthographic);
  w.set_fov_y_radians(view.fovYRadians);
  w.set_ortho_height(view.orthoHeight);
  w.set_near_distance(view.nearDistance);
  w.set_width(static_cast<uint32_t>(std::max(0, view.width)));
  w.set_height(static_cast<uint32_t>(std::max(0, view.height)));
  w.set_tolerance_pixels(view.tolerancePixels);
  return w;
}

wire::ClientMessage subscribeWithView(uint64_t documentId, const View& view, uint64_t budget) {
  wire::ClientMessage m;
  m.mutable_subscribe()->set_document_id(documentId);
  m.mutable_subscribe()->mutable_profile()->set_triangle_budget(budget);
  *m.mutable_subscribe()->mutable_view() = viewToWire(view);
  return m;
}

wire::ClientMessage setView(uint64_t documentId, const View& view) {
  wire::ClientMessage m;
  m.mutable_set_view()->set_document_id(documentId);
  *m.mutable_set_view()->mutable_view() = viewToWire(view);
  return m;
}

}  // namespace tessera::client
