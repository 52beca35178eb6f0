// A mesh as the bytes a command carries (CreateDocument.mesh,
// AddMorphKey.mesh; docs/PROTOCOL.md §13.2, §14): a file's bytes with its
// wire format, or arrays written as an OFF file by core's exporter.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/polygon_soup.h"
#include "core/util/vec3.h"
#include "protocol/tessera.pb.h"

namespace tessera::python {

// The wire format of a mesh file by its extension (as `tessera remote
// create` chooses it); ValueError for another.
wire::MeshFormat meshFormatOf(const std::string& path);

// Points and faces as the bytes of an OFF file, written by core's exporter
// (shortest round-trip decimals: lossless, core/io/mesh_export.h) through a
// temporary file that is removed before returning. Throws Failure.
std::string offBytes(const std::vector<Vec3>& points, const PolygonSoup& faces);

}  // namespace tessera::python
