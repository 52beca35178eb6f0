// Subscriptions and what they deliver (docs/PROTOCOL.md §6, §16): the
// session's subscribe, set_view, unsubscribe and wait_for, and
// tessera.DocumentView, client::DocumentView's decoded regions as NumPy
// arrays.
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>

#include "client/lib/view_wire.h"
#include "client/python/bindings.h"
#include "client/python/errors.h"
#include "client/python/numpy_arrays.h"
#include "client/python/replies.h"

namespace tessera::python {

namespace {

using ViewPtr = std::shared_ptr<client::DocumentView>;

// One decoded region, copied into arrays.
struct RegionArrays {
  uint64_t regionId = 0;
  py::array_t<double> positions, normals;
  py::array_t<int32_t> triangles;
  py::array_t<uint64_t> vertexIds;
};

RegionArrays regionArrays(uint64_t id, const RegionMesh& mesh) {
  return {id, pointsArray(mesh.positions), pointsArray(mesh.normals), trianglesArray(mesh.triangles),
          idsArray(mesh.vertexIds)};
}

// Every region one after the other, in region id order: positions and ids
// row by row, triangles renumbered into the concatenation.
RegionMesh concatenated(const client::DocumentView& view) {
  RegionMesh all;
  for (const auto& [id, region] : view.regions()) {
    const int first = static_cast<int>(all.positions.size());
    all.positions.insert(all.positions.end(), region.positions.begin(), region.positions.end());
    all.normals.insert(all.normals.end(), region.normals.begin(), region.normals.end());
    all.vertexIds.insert(all.vertexIds.end(), region.vertexIds.begin(), region.vertexIds.end());
    for (const auto& t : region.triangles)
      all.triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
  }
  return all;
}

View viewOf(std::array<double, 3> eye, std::array<double, 3> forward, std::array<double, 3> up, int width,
            int height, double fovY, std::optional<double> orthoHeight, double nearDistance,
            double tolerance) {
  View v;
  v.eye = {eye[0], eye[1], eye[2]};
  v.forward = {forward[0], forward[1], forward[2]};
  v.up = {up[0], up[1], up[2]};
  v.width = width;
  v.height = height;
  v.fovYRadians = fovY;
  if (orthoHeight) {
    v.projection = Projection::kOrthographic;
    v.orthoHeight = *orthoHeight;
  }
  v.nearDistance = nearDistance;
  v.tolerancePixels = tolerance;
  return v;
}

constexpr const char* kViewArgsDoc =
    "    eye, forward, up: the camera (forward need not be unit, nor parallel to up).\n"
    "    width, height: the viewport in pixels.\n"
    "    fov_y: the vertical field of view in radians (perspective).\n"
    "    ortho_height: orthographic instead, showing this world height.\n"
    "    near: the near distance; tolerance: the screen-space error in pixels.";

}  // namespace

void bindViews(py::module_& m) {
  py::class_<RegionArrays>(m, "Region",
                           "One decoded region of a subscription's surface (docs/PROTOCOL.md 6.2).")
      .def_readonly("region_id", &RegionArrays::regionId, "The region's id, stable across versions.")
      .def_readonly("positions", &RegionArrays::positions,
                    "(N, 3) float64, dequantized as a Draco decoder does.")
      .def_readonly("normals", &RegionArrays::normals, "(N, 3) float64 unit limit normals.")
      .def_readonly("triangles", &RegionArrays::triangles,
                    "(M, 3) int32 indices into this region's vertices.")
      .def_readonly("vertex_ids", &RegionArrays::vertexIds,
                    "(N,) uint64 packed id of the control vertex each vertex is the limit of\n"
                    "(empty with a profile without ids).");

  py::class_<client::DocumentView, ViewPtr>(
      m, "DocumentView",
      "A subscribed document as this session sees it (client::DocumentView): the\n"
      "decoded regions of its profile, kept current by the snapshots and deltas\n"
      "that Session.receive() and Session.wait_for() read. Arrays are copies taken\n"
      "when asked for.")
      .def_property_readonly("document_id", &client::DocumentView::documentId, "The subscribed document.")
      .def_property_readonly("version", &client::DocumentView::version,
                             "The document version the regions show.")
      .def_property_readonly("ready", &client::DocumentView::ready,
                             "A snapshot has arrived and no gap since.")
      .def_property_readonly("needs_resync", &client::DocumentView::needsResync,
                             "A delta did not follow the version held: the view waits for a snapshot\n"
                             "(subscribe again to get one at once).")
      .def_property_readonly("triangle_count", &client::DocumentView::numTriangles,
                             "Triangles over all regions held.")
      .def_property_readonly("view_complete", &client::DocumentView::viewComplete,
                             "A view-dependent subscription holds every tile its view needs.")
      .def_property_readonly("bytes_received", &client::DocumentView::bytesReceived,
                             "Encoded region bytes received so far.")
      .def(
          "regions",
          [](const client::DocumentView& v) {
            std::map<uint64_t, RegionArrays> out;
            for (const auto& [id, region] : v.regions()) out.emplace(id, regionArrays(id, region));
            return out;
          },
          "Every region held, as a dict from region id to tessera.Region.")
      .def(
          "positions", [](const client::DocumentView& v) { return pointsArray(concatenated(v).positions); },
          "(N, 3) float64: every region's vertices, region after region (by region id).")
      .def(
          "vertex_ids", [](const client::DocumentView& v) { return idsArray(concatenated(v).vertexIds); },
          "(N,) uint64: the packed control-vertex id of each row of positions().")
      .def(
          "normals", [](const client::DocumentView& v) { return pointsArray(concatenated(v).normals); },
          "(N, 3) float64: the unit limit normal of each row of positions().")
      .def(
          "triangles",
          [](const client::DocumentView& v) { return trianglesArray(concatenated(v).triangles); },
          "(M, 3) int32: every region's triangles, as rows of positions().")
      .def(
          "surface", [](const client::DocumentView& v) { return meshArrays(v.surface()); },
          "The regions merged into one tessera.Mesh, vertices shared between regions\n"
          "joined (by vertex id and normal).")
      .def("surface_hash", &client::DocumentView::surfaceHash,
           "The surface hash of the regions held (docs/PROTOCOL.md 6.5).")
      .def_property_readonly("announced_surface_hash", &client::DocumentView::announcedSurfaceHash,
                             "The server's surface hash for the version held; 0 if it sent none.")
      .def(
          "verify", [](const client::DocumentView& v) { check(v.verifySurface()); },
          "Raises tessera.Error when the regions held differ from what the server\n"
          "says it sent (their surface hashes differ).")
      .def("__repr__", [](const client::DocumentView& v) {
        return "<tessera.DocumentView document " + std::to_string(v.documentId()) + ", version " +
               std::to_string(v.version()) + ", " + std::to_string(v.regions().size()) + " regions>";
      });
}

void bindSubscriptions(SessionClass& session) {
  session.def(
      "subscribe",
      [](RemoteSession& s, uint64_t document, uint32_t baseLevel, uint32_t maxLevel, double angle,
         uint64_t budget, uint32_t fidelity, bool vertexIds, bool withCommands, std::optional<double> morphT,
         std::optional<double> timeout) {
        wire::ClientMessage m;
        auto* sub = m.mutable_subscribe();
        sub->set_document_id(document);
        sub->set_with_commands(withCommands);
        auto* p = sub->mutable_profile();
        p->set_base_level(baseLevel);
        p->set_max_level(maxLevel);
        p->set_angle_threshold_degrees(angle);
        p->set_triangle_budget(budget);
        p->set_fidelity(fidelity);
        p->set_omit_vertex_ids(!vertexIds);
        if (morphT) p->set_morph_t(*morphT);
        // Watched before the Ack: the snapshot follows it at once.
        ViewPtr previous = s.view(document);
        s.watch(document);
        try {
          return ackOf(s.call(m, timeout));
        } catch (...) {
          s.restoreView(document, previous);
          throw;
        }
      },
      py::arg("document_id"), py::kw_only(), py::arg("base_level") = 2, py::arg("max_level") = 5,
      py::arg("angle_threshold") = 10.0, py::arg("triangle_budget") = 0, py::arg("fidelity") = 0,
      py::arg("vertex_ids") = true, py::arg("with_commands") = false, py::arg("morph_t") = py::none(),
      py::arg("timeout") = py::none(),
      "Subscribes to an open document with a level-of-detail profile\n"
      "(docs/PROTOCOL.md 7.1): every base face refined at least to base_level, never\n"
      "beyond max_level, further where limit normals differ by more than\n"
      "angle_threshold degrees; triangle_budget 0 is the server's limit. A new\n"
      "subscription replaces the previous one and its view. morph_t: a morph\n"
      "document's surface at that time in [0, 1] (docs/PROTOCOL.md section 14), rounded\n"
      "to a multiple of 1/10000; None: key 0 as it is. REJECT_REASON_INVALID_ARGUMENT\n"
      "for a time on a document with one key or outside [0, 1].\n\n"
      "Returns the tessera.Ack (version: the snapshot's). The snapshot and later\n"
      "deltas are read by receive() / wait_for() into Session.view(document_id).");
  session.def(
      "subscribe_view",
      [](RemoteSession& s, uint64_t document, std::array<double, 3> eye, std::array<double, 3> forward,
         std::array<double, 3> up, int width, int height, double fovY, std::optional<double> orthoHeight,
         double nearDistance, double tolerance, uint64_t budget, std::optional<double> timeout) {
        const View v = viewOf(eye, forward, up, width, height, fovY, orthoHeight, nearDistance, tolerance);
        ViewPtr previous = s.view(document);
        s.watch(document);
        try {
          return ackOf(s.call(client::subscribeWithView(document, v, budget), timeout));
        } catch (...) {
          s.restoreView(document, previous);
          throw;
        }
      },
      py::arg("document_id"), py::kw_only(), py::arg("eye"), py::arg("forward"),
      py::arg("up") = std::array{0.0, 1.0, 0.0}, py::arg("width"), py::arg("height"), py::arg("fov_y") = 0.8,
      py::arg("ortho_height") = py::none(), py::arg("near") = 1e-3, py::arg("tolerance") = 1.0,
      py::arg("triangle_budget") = 0, py::arg("timeout") = py::none(),
      (std::string("A view-dependent subscription (docs/VIEWS.md, PROTOCOL.md section 16): the\n"
                   "regions are tiles chosen for this camera; the last delta of a view is marked\n"
                   "view_complete.\n\nArgs:\n") +
       kViewArgsDoc + "\n\nReturns the tessera.Ack.")
          .c_str());
  session.def(
      "set_view",
      [](RemoteSession& s, uint64_t document, std::array<double, 3> eye, std::array<double, 3> forward,
         std::array<double, 3> up, int width, int height, double fovY, std::optional<double> orthoHeight,
         double nearDistance, double tolerance) {
        s.send(client::setView(
            document, viewOf(eye, forward, up, width, height, fovY, orthoHeight, nearDistance, tolerance)));
      },
      py::arg("document_id"), py::kw_only(), py::arg("eye"), py::arg("forward"),
      py::arg("up") = std::array{0.0, 1.0, 0.0}, py::arg("width"), py::arg("height"), py::arg("fov_y") = 0.8,
      py::arg("ortho_height") = py::none(), py::arg("near") = 1e-3, py::arg("tolerance") = 1.0,
      (std::string("Moves the camera of a view-dependent subscription. No reply when valid: the\n"
                   "tiles that change come as deltas; a refused view comes back as a 'reject'\n"
                   "from receive().\n\nArgs:\n") +
       kViewArgsDoc)
          .c_str());
  session.def(
      "unsubscribe",
      [](RemoteSession& s, uint64_t document, std::optional<double> timeout) {
        wire::ClientMessage m;
        m.mutable_unsubscribe()->set_document_id(document);
        AckReply ack = ackOf(s.call(m, timeout));
        s.stopWatching(document);
        return ack;
      },
      py::arg("document_id"), py::arg("timeout") = py::none(), "Ends the subscription; its view is dropped.");
  session.def(
      "view", [](const RemoteSession& s, uint64_t document) { return s.view(document); },
      py::arg("document_id"), "The tessera.DocumentView of a subscribed document, or None.");
  session.def(
      "wait_for",
      [](RemoteSession& s, uint64_t document, std::optional<uint64_t> version, double timeout) {
        ViewPtr v = s.view(document);
        if (!v)
          throw py::value_error("document " + std::to_string(document) +
                                " is not subscribed on this session");
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
        auto done = [&] { return v->ready() && (!version || v->version() >= *version); };
        while (!done()) {
          const double left =
              std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
          if (left <= 0) {
            throw Failure(
                timeoutError("document " + std::to_string(document) + ": no " +
                             (version ? "version " + std::to_string(*version) : std::string("snapshot")) +
                             " within " + std::to_string(timeout) + " s (the view holds version " +
                             std::to_string(v->version()) + ")"));
          }
          // In slices, so that Ctrl-C is seen while waiting.
          s.receive(std::min(left, 0.25));
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        }
        return v;
      },
      py::arg("document_id"), py::arg("version") = py::none(), py::arg("timeout") = 10.0,
      "Reads messages (as receive() does) until the document's view is ready and, if\n"
      "`version` is given, shows that version or a later one. Returns the\n"
      "tessera.DocumentView; raises tessera.Timeout after `timeout` seconds.");
}

}  // namespace tessera::python
