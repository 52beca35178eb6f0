// Regions as one mesh: vertices shared by identity (vertex id and normal,
// so crease sides stay apart), for export and for checks on the union.
#pragma once

#include <cstdint>
#include <map>

#include "core/mesh/surface_mesh.h"
#include "core/tessellation/region_codec.h"

namespace tessera {

SurfaceMesh mergeRegions(const std::map<uint64_t, RegionMesh>& regions);

}  // namespace tessera
