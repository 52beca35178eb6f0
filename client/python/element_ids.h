// Element ids as Python passes them (docs/PROTOCOL.md §3.1): the packed
// 64-bit int a region's vertex_ids array holds, or the text form "v3:1234"
// / "e2:55" that `tessera doc info` prints.
#pragma once

#include <pybind11/pybind11.h>

#include <vector>

#include "core/hierarchy/ids.h"

namespace tessera::python {

namespace py = pybind11;

// An int (packed) or a str ("v3:1234"); anything else raises TypeError,
// unparsable text tessera.Error.
VertexId vertexIdOf(const py::handle& value);
EdgeId edgeIdOf(const py::handle& value);
// One id, or an iterable of them (a list, a NumPy array of packed ids).
std::vector<VertexId> vertexIdsOf(const py::handle& value);

}  // namespace tessera::python
