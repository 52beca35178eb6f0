// Edit-script commands (core/document/edit_script.h) as wire commands
// (docs/PROTOCOL.md, the edit commands): how `tessera remote edit` and the
// tests send a script to a server, written once.
#pragma once

#include <cstdint>

#include "core/document/edit_script.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::client {

// One command for an EditBatch (the batch names the document), to a morph
// document's key `key`. A remove has no wire form: an empty command.
wire::EditCommand editCommandOf(const ScriptCommand& command, uint32_t key = 0);

// One command sent on its own to `document`; a remove is kUnsupported.
Expected<wire::ClientMessage> clientMessageOf(const ScriptCommand& command, uint64_t document,
                                              uint32_t key = 0);

}  // namespace tessera::client
