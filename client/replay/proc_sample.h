// The server process's CPU time and resident memory from /proc, for load
// runs given --server-pid (docs/REPLAY.md §3).
#pragma once

#include <cstdint>

namespace tessera::replay {

struct ProcSample {
  bool ok = false;
  double cpuSeconds = 0;  // utime + stime
  int64_t rssBytes = 0;   // VmRSS
};

// ok is false for pid <= 0 or a process that cannot be read.
ProcSample sampleProcess(int pid);

}  // namespace tessera::replay
