// One edit in the binary layout of docs/DOCUMENT_FORMAT.md: shared by the
// document file and by the server's journal, so a journaled edit replays bit
// for bit.
#pragma once

#include "core/hierarchy/edit.h"
#include "core/util/byte_io.h"
#include "core/util/status.h"

namespace tessera {

void writeEdit(const Edit& edit, ByteWriter& w);
// Errors name the reader's source and the edit.
Expected<Edit> readEdit(ByteReader& r);

}  // namespace tessera
