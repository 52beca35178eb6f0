// The heap policy of processes that refine, free and refine again: the
// server, and the benchmarks that measure what it does.
//
// glibc gives memory back to the kernel on its own: the top of the heap
// whenever more than M_TRIM_THRESHOLD of it is free, and every block above
// M_MMAP_THRESHOLD (128 KiB at first) as soon as it is freed, since such
// blocks get mappings of their own. A level's arrays are that large, so each
// rebuild or growth of a hierarchy faulted its pages in again: under perf,
// 40 % of tessera_bench_scheme's Catmull-Clark hierarchy at level 2 was the
// kernel's page-fault and unmap paths (docs/PERFORMANCE.md "Catmull-Clark
// hierarchy: the heap kept for reuse"). keepFreedMemoryForReuse() keeps
// blocks up to 32 MiB (glibc's largest mmap threshold) in the heap and lets
// up to 1 GiB of free heap stay mapped, to be reused. Memory then goes back
// only when asked: the server trims the heap after bulk work and when a
// document is released (server/document/bulk_release.h), so its resident
// memory still follows what it holds at those points.
#pragma once

namespace tessera {

// Process-wide; call once at start, before threads. Returns false where
// the C library refused (not glibc, or a value out of its range).
bool keepFreedMemoryForReuse();

}  // namespace tessera
