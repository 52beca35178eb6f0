// A document at one level as a subdivision cage: the level's control points
// and faces with the level's tags (semi-sharp values decayed as refinement
// left them, sharpness edits made at that level or above applied), its
// scheme, boundary rule and crease method. Refined again by the same rules,
// by Tessera or by OpenSubdiv, the cage gives the document's finer levels
// as long as no edit is made below it (docs/FORMATS.md "USD", the cage).
// What `tessera doc export --level N -o OUT.usda` writes.
#pragma once

#include "core/document/document.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/status.h"

namespace tessera {

// Infinitely sharp tags are kSharpnessInfinite (10), OpenSubdiv's value;
// boundary edges are written sharp as the level holds them.
Expected<SurfaceMesh> documentCage(const Document& document, int level);

}  // namespace tessera
