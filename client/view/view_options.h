// The command line of tessera-view (docs/VIEWER.md), parsed with CLI11.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/tessellation/region_codec.h"
#include "core/util/status.h"

namespace tessera::view {

struct ViewOptions {
  std::string host = "127.0.0.1";
  uint16_t port = 7878;
  std::string token;
  std::string name = "tessera-view";
  uint64_t document = 0;
  // A view-dependent subscription (docs/VIEWER.md "Views"): tiles chosen
  // for the camera, sent again as it moves; the profile's levels are not
  // used then. The command line's default (parseViewOptions); options
  // built in code choose it themselves.
  bool views = false;
  double tolerancePixels = 1;
  // The region codec asked for (Subscribe.codec, docs/REGION_ENCODING.md
  // "meshopt regions"). The server serves views in Draco only, so meshopt
  // goes with a profile subscription (checkCodec).
  RegionCodec codec = RegionCodec::kDraco;
  bool levelColours = false;  // with views: tiles coloured by level (key L)
  // The LOD profile to subscribe with when not `views`.
  uint32_t baseLevel = 1;
  uint32_t maxLevel = 3;
  double angle = 15;
  // A morph document (docs/VIEWER.md, "Morph documents"): show it at this
  // time (LodProfile.morph_t) instead of key 0 live; P plays it at
  // `morphRate` (t per second).
  std::optional<double> morphT;
  double morphRate = 0.25;
  // Show every time through the coarse stream (control points refined here),
  // paused too; by default only playing uses it.
  bool morphCoarse = false;
  // The level whose control vertices are shown and dragged.
  int controlLevel = 0;
  int width = 800, height = 600;
  bool wireframe = false;
  bool regionColours = false;
  bool hud = true;
  bool hudCollapsed = false;   // one line instead of the full HUD (key H)
  bool controlPoints = false;  // draw the control vertices (key V)
  bool cage = false;           // draw the control cage of that level as polygons (key O)
  bool gizmo = true;           // the axes in the bottom-left corner (key G)
  bool matcap = false;         // matcap shading instead of the three lights (key M)
  // Multisample anti-aliasing: samples per pixel, 0 for none (capped by the driver).
  int msaa = 4;
  // Client-side refinement (docs/VIEWER.md, "Client-side refinement"): at
  // most this many splits per edge, 0 for none.
  int refine = 0;
  // Headless: render `frames` frames once the document is in, write the PNG, exit.
  std::string screenshot;
  int frames = 30;
  // Headless self-test of picking: pick the visible control vertex nearest
  // the window centre and drag it by (dx, dy) pixels with synthetic mouse
  // input, wait for the edits' deltas, then count the frames.
  bool drag = false;
  int dragX = 0, dragY = 0;
  // Headless self-test of the edit keys: pick an edge, press E, K, Ctrl+Z,
  // Ctrl+Z, Ctrl+Y (self_test.h) and print the surface hash after each.
  bool editKeys = false;
  // Keep ConnectionStats::surfaceHash (set by editKeys and --surface-hash,
  // and by tests); headless mode prints it at the end.
  bool hashSurfaces = false;
  double timeoutSeconds = 30;  // to connect and receive the first snapshot
  // When the process started: headless mode times its first and whole
  // pictures from here (connecting and subscribing included).
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  bool help = false;
  bool version = false;
};

// The --help text.
std::string viewHelp();

// Meshopt with a view-dependent subscription is refused, naming the
// conflict and what to pass instead: the server sends tiles in Draco only
// (docs/REGION_ENCODING.md "meshopt regions", "Where it is served").
Status checkCodec(const ViewOptions& options);

// Errors name the option and the reason. --help and --version set `help`
// and `version` and skip the checks of the other options.
Expected<ViewOptions> parseViewOptions(const std::vector<std::string>& args);

}  // namespace tessera::view
