// Store benchmark: durable journal appends per second, and the latency each
// producer sees from append to durable acknowledgement, with 1, 8 and 64
// concurrent producers; with group commit (grouped:1) and with one
// transaction, hence one fsync, per append (grouped:0).
//
// Each producer is a thread with its own document calling appendSync in a
// loop, as a document strand of the server waits for its edit to be durable.
//
//   build/store/bench/tessera_bench_store
//   TESSERA_STORE_BENCH_DIR=/mnt/other-disk build/store/bench/tessera_bench_store
//
// Results depend on the disk's fsync latency above all: run it on the disk
// that will hold the data directory (the default is the temp directory).
#include <benchmark/benchmark.h>

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "bench/percentile.h"
#include "server/store/sqlite_store.h"

namespace tessera {
namespace {

std::string benchRoot() {
  const char* configured = std::getenv("TESSERA_STORE_BENCH_DIR");
  return configured != nullptr ? std::string(configured) : std::filesystem::temp_directory_path().string();
}

// One run's store, shared by its producer threads: built by thread 0 before
// the timed loop and torn down by it after (the loop's start and end are
// barriers across the threads of a run).
struct Run {
  std::string directory;
  std::unique_ptr<store::SqliteStore> store;
  std::vector<store::DocumentId> documents;      // one per producer
  std::vector<std::vector<double>> latenciesUs;  // one per producer
  store::StoreStats statsBefore;
};
std::unique_ptr<Run> currentRun;

std::unique_ptr<Run> startRun(int producers, bool grouped, std::string& error) {
  auto run = std::make_unique<Run>();
  std::string pattern = benchRoot() + "/tessera-store-bench-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    error = "mkdtemp failed under " + benchRoot();
    return nullptr;
  }
  run->directory = pattern;
  store::SqliteStoreOptions options;
  options.maxBatchWrites = grouped ? 4096 : 1;
  auto store = store::SqliteStore::open(run->directory, options);
  if (!store.isOk()) {
    error = store.status().toString();
    return nullptr;
  }
  run->store = std::move(store).value();
  for (int p = 0; p < producers; ++p) {
    auto id = run->store->createDocument("producer " + std::to_string(p), "base");
    if (!id.isOk()) {
      error = id.status().toString();
      return nullptr;
    }
    run->documents.push_back(*id);
  }
  run->latenciesUs.resize(producers);
  run->statsBefore = run->store->stats();
  return run;
}

void finishRun(benchmark::State& state, Run& run) {
  std::vector<double> all;
  for (const std::vector<double>& latencies : run.latenciesUs)
    all.insert(all.end(), latencies.begin(), latencies.end());
  std::sort(all.begin(), all.end());
  const store::StoreStats stats = run.store->stats();
  const double entries = static_cast<double>(stats.entriesCommitted - run.statsBefore.entriesCommitted);
  const double batches = static_cast<double>(stats.batches - run.statsBefore.batches);
  // Counters of a threaded run are summed over threads; only thread 0 sets these.
  state.counters["p50_us"] = tessera::bench::percentile(all, 0.50);
  state.counters["p99_us"] = tessera::bench::percentile(all, 0.99);
  state.counters["max_us"] = all.empty() ? 0.0 : all.back();
  state.counters["per_batch"] = batches > 0 ? entries / batches : 0.0;
  run.store->close();
  std::error_code ignored;
  std::filesystem::remove_all(run.directory, ignored);
}

void BM_DurableAppends(benchmark::State& state) {
  const bool grouped = state.range(0) != 0;
  if (state.thread_index() == 0) {
    std::string error;
    currentRun = startRun(state.threads(), grouped, error);
    if (!currentRun) state.SkipWithError(error.c_str());
  }
  const std::string entry(64, 'e');  // about one serialized edit command
  uint64_t version = 0;
  for (auto _ : state) {
    Run& run = *currentRun;
    const int producer = state.thread_index();
    const auto start = std::chrono::steady_clock::now();
    Status status = run.store->appendSync(run.documents[producer], ++version, "bench", entry);
    const auto elapsed = std::chrono::steady_clock::now() - start;
    run.latenciesUs[producer].push_back(std::chrono::duration<double, std::micro>(elapsed).count());
    if (!status.isOk()) {
      state.SkipWithError(status.toString().c_str());
      break;
    }
  }
  state.SetItemsProcessed(state.iterations());
  if (state.thread_index() == 0 && currentRun) {
    finishRun(state, *currentRun);
    currentRun.reset();
  }
}
BENCHMARK(BM_DurableAppends)
    ->ArgName("grouped")
    ->Arg(1)
    ->Arg(0)
    ->Threads(1)
    ->Threads(8)
    ->Threads(64)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  benchmark::AddCustomContext("store_dir", tessera::benchRoot());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
