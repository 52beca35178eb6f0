#include "server/document/view_request.h"

#include <algorithm>

namespace tessera::server {

Expected<View> viewFromWire(const wire::View& w) {
  auto vec = [](const wire::Vec3& v) { return Vec3(v.x(), v.y(), v.z()); };
  View view;
  view.eye = vec(w.eye());
  view.forward = vec(w.forward());
  view.up = vec(w.up());
  view.projection = w.orthographic() ? Projection::kOrthographic : Projection::kPerspective;
  view.fovYRadians = w.fov_y_radians();
  view.orthoHeight = w.ortho_height();
  view.nearDistance = w.near_distance();
  // Beyond int range is out of range anyway; kept so the check names it.
  view.width = static_cast<int>(std::min<uint32_t>(w.width(), 1u << 30));
  view.height = static_cast<int>(std::min<uint32_t>(w.height(), 1u << 30));
  view.tolerancePixels = w.tolerance_pixels();
  TESSERA_RETURN_IF_ERROR(view.check());  // its messages start "view: "
  return view;
}

}  // namespace tessera::server
