// Random edit histories as edit-script lines (core/document/edit_script.h),
// for the tests that hold the acceptance rule to being a function of the
// history alone: the same lines are applied offline, by `tessera doc edit
// --each`, and on servers with and without viewers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/quantization_grid.h"

namespace tessera::testing {

// `count` lines for `doc`: direct-manipulation moves at levels 0..2, about a
// third of them aimed near or past the faces of `grid` (so that some are
// refused, and some land where the limits only a viewer holds would leave
// it); plain offsets at levels 1..2; edge creases and vertex corners at
// levels 0..1; undos and redos of earlier edit ids, some of them invalid.
std::vector<std::string> randomScriptLines(const Document& doc, const QuantizationGrid& grid, int count,
                                           uint32_t seed);

}  // namespace tessera::testing
