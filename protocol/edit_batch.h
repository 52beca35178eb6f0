// The bound on an EditBatch (docs/PROTOCOL.md, EditBatch): what a server
// applies as one version and a client may send in one message. A larger
// batch is refused with REJECT_REASON_LIMIT_EXCEEDED before anything is
// applied; a client splits nothing on its own (that would not be atomic).
#pragma once

#include <cstddef>

namespace tessera {

inline constexpr int kMaxEditBatchCommands = 1024;

}  // namespace tessera
