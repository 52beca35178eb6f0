// Cameras that move, for load runs of view-dependent viewers (docs/REPLAY.md
// §3, docs/VIEWS.md): each viewer follows its own path around a target
// sphere, drawn from its own seed, so that a hundred viewers ask for a
// hundred different sets of tiles.
//
//   orbit:  around the target at 1.5 to 3 radii, at its own elevation and
//           phase, one turn in 20 s;
//   zoom:   along its own direction, from 3 radii in to 0.3 and out again
//           every 10 s;
//   fly:    through the target sphere on its own line, looking ahead, once
//           every 10 s;
//   random: a new random camera around the target every second.
#pragma once

#include <cstdint>
#include <string>

#include "core/util/status.h"
#include "core/util/vec3.h"
#include "core/view/view.h"

namespace tessera::replay {

enum class CameraPathKind { kOrbit, kZoom, kFly, kRandom };

struct CameraPaths {
  CameraPathKind kind = CameraPathKind::kOrbit;
  Vec3 centre;
  double radius = 1;
  int width = 390, height = 844;
  double tolerancePixels = 1;
  double viewsPerSecond = 5;  // SetViews each viewer sends
  uint64_t seed = 1;
};

// "orbit", "zoom", "fly" or "random".
Expected<CameraPathKind> cameraPathKind(const std::string& name);
const char* cameraPathName(CameraPathKind kind);

// Viewer `viewer`'s camera `seconds` into the run.
View cameraAt(const CameraPaths& paths, int viewer, double seconds);

}  // namespace tessera::replay
