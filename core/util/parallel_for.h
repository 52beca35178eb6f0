// Independent items of work spread over the machine's cores: the calling
// thread and up to `threads - 1` more each take the next item until none
// is left. The helpers are threads kept waiting between calls (starting one
// costs tens of microseconds), so it pays for items of tens of microseconds
// and more, such as building or Draco-encoding a region (docs/PERFORMANCE.md
// "Edit to encoded region deltas"). A call never waits for a helper busy
// elsewhere: calls from several threads, and calls nested in an item, work
// on with the threads they have. `body` must not throw; items report
// failure through what they write.
#pragma once

#include <cstddef>
#include <functional>

namespace tessera {

// The threads parallelFor is given by the steps that use it: the
// hardware's count, at most 4, unless setWorkThreads chose another.
unsigned workThreads();
// 0: the default again. For a process's options and for benchmarks that
// measure one thread against several in the same run.
void setWorkThreads(unsigned threads);

// Calls body(i) once for every i in [0, n), in no particular order, and
// returns when every call has returned. With n < 2 or threads < 2 it runs
// on the calling thread alone.
void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body);

}  // namespace tessera
