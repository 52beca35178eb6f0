// The one quantization grid of a document (docs/REGION_ENCODING.md "One grid
// per document, bit-identical borders"): every
// region of every LOD profile is encoded on it, so border vertices decode
// identically on both sides. It spans the base mesh's box grown to five
// times its largest extent, so edits have room, with the bits that keep the
// decoded error within 1e-4 of the base box's diagonal. A surface leaving
// it cannot be encoded: servers refuse such edits.
#pragma once

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"

namespace tessera {

Expected<QuantizationGrid> documentGrid(const Document& doc);

}  // namespace tessera
