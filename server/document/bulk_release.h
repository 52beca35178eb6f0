// Memory a document held, given back off the interactive workers
// (docs/ARCHITECTURE.md, "Bulk work"): a closed document or a tessellation
// of millions of triangles takes seconds to free, so the last reference is
// dropped on a bulk thread rather than on the worker that held it (it may
// owe a small document an edit), and the heap is trimmed after it, so that
// resident memory follows what is held.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <memory>

namespace tessera::server {

// Drops `held` on `bulk` (the caller gives up its reference), then trims
// the heap (malloc_trim walks the heap, so it too runs there).
void releaseOnBulk(const boost::asio::any_io_executor& bulk, std::shared_ptr<void> held);

// Trims the heap on `bulk`, after bulk work whose buffers are freed.
void trimHeapOnBulk(const boost::asio::any_io_executor& bulk);

}  // namespace tessera::server
