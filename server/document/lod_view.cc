#include "server/document/lod_view.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <span>
#include <vector>

#include "core/tessellation/document_bounds.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/surface_hash.h"
#include "core/util/parallel_for.h"
#include "server/base/log.h"
#include "server/document/replies.h"

namespace tessera::server {

using Clock = std::chrono::steady_clock;

Expected<std::shared_ptr<const std::string>> encodeViewRegion(const LodView& view, uint64_t region,
                                                              bool idsInline, const EncodeContext& context,
                                                              RegionCodec codec) {
  const auto start = Clock::now();
  RegionHeader header{region,       context.version, view.layout.at(region), view.tessellation->profile(),
                      context.grid, idsInline};
  header.codec = codec;
  if (header.profile.vertexIds && idsInline && !view.tessellation->regionsAreGroups()) {
    // Ids as points of the region's lattice: a third of the bytes they
    // took as eight-byte labels (region_lattice.h). A group of base faces
    // has no one root face: its ids stay labels.
    auto frame = regionFrame(context.source.hierarchy(), context.source.counts(), FaceId::fromPacked(region));
    if (frame.isOk()) header.frame = *frame;
  }
  const RegionMesh& mesh = view.tessellation->regions().at(region);
  const std::optional<RegionMesh> clamped = clampedToGrid(mesh, context.grid);
  TESSERA_ASSIGN_OR_RETURN(std::string bytes, encodeRegion(header, clamped ? *clamped : mesh));
  context.stats.encodeMicros += microsSince(start);
  context.stats.encodeLatency.addMicros(microsSince(start));
  ++context.stats.regionsEncoded;
  return std::make_shared<const std::string>(std::move(bytes));
}

namespace {

// encodeViewRegion for each of `regions`, in order, on several cores (each
// is independent and takes about a hundred microseconds; docs/
// PERFORMANCE.md "Edit to encoded region deltas"); `idsInline(i)` for the
// i-th.
std::vector<Expected<std::shared_ptr<const std::string>>> encodeViewRegions(
    const LodView& view, std::span<const uint64_t> regions, const std::function<bool(size_t)>& idsInline,
    const EncodeContext& context, RegionCodec codec) {
  std::vector<Expected<std::shared_ptr<const std::string>>> encodings(regions.size(),
                                                                      internalError("not encoded"));
  parallelFor(regions.size(), workThreads(), [&](size_t i) {
    encodings[i] = encodeViewRegion(view, regions[i], idsInline(i), context, codec);
  });
  return encodings;
}

size_t codecIndex(RegionCodec codec) {
  return static_cast<size_t>(codec);
}

}  // namespace

std::vector<RegionCodec> heldCodecs(const LodView& view) {
  std::array<bool, kRegionCodecCount> held{};
  for (const auto& [session, codec] : view.codecOf) {
    auto who = view.subscribers.find(session);
    if (who != view.subscribers.end() && !who->second.expired()) held[codecIndex(codec)] = true;
  }
  std::vector<RegionCodec> codecs;
  for (size_t c = 0; c < held.size(); ++c) {
    if (held[c]) codecs.push_back(static_cast<RegionCodec>(c));
  }
  return codecs;
}

std::string deltaKey(const std::string& viewKey, RegionCodec codec) {
  return codec == RegionCodec::kDraco ? viewKey : viewKey + "|" + regionCodecName(codec);
}

void rehashRegion(LodView& view, uint64_t region, const QuantizationGrid& grid, bool removed) {
  auto [it, fresh] = view.regionHashes.try_emplace(region, 0);
  view.surfaceHash -= it->second;
  if (removed) {
    view.regionHashes.erase(it);
    return;
  }
  const RegionMesh& mesh = view.tessellation->regions().at(region);
  const std::optional<RegionMesh> clamped = clampedToGrid(mesh, grid);
  it->second =
      regionSurfaceHashOnGrid(clamped ? *clamped : mesh, grid, view.tessellation->profile().vertexIds);
  view.surfaceHash += it->second;
}

std::vector<std::pair<RegionCodec, DeltaContent>> buildDeltas(LodView& view,
                                                              const Tessellation::Changes& changes,
                                                              const EncodeContext& context,
                                                              uint64_t documentId, const DeltaContent& base) {
  // A region that only moved keeps its layout: its delta leaves the ids
  // out (a third of its bytes) and a later snapshot encodes them afresh.
  const bool withIds = view.tessellation->profile().vertexIds;
  for (uint64_t region : changes.changed) rehashRegion(view, region, context.grid);
  for (uint64_t region : changes.removed) rehashRegion(view, region, context.grid, /*removed=*/true);
  std::vector<char> idsInlineOf(changes.changed.size());
  for (size_t i = 0; i < changes.changed.size(); ++i) {
    const uint64_t region = changes.changed[i];
    const bool relaid = std::binary_search(changes.relaid.begin(), changes.relaid.end(), region);
    if (relaid) view.layout[region] = context.version;
    idsInlineOf[i] = relaid || !withIds;
  }
  const std::vector<RegionCodec> codecs = heldCodecs(view);
  std::vector<std::pair<RegionCodec, DeltaContent>> deltas;
  for (size_t c = 0; c < view.encoded.size(); ++c) {
    const RegionCodec codec = static_cast<RegionCodec>(c);
    auto& cache = view.encoded[c];
    if (std::find(codecs.begin(), codecs.end(), codec) == codecs.end()) {
      cache.clear();  // stale from now on; a subscriber that comes back gets it encoded afresh
      continue;
    }
    DeltaContent& delta = deltas.emplace_back(codec, base).second;
    delta.surfaceHash = view.surfaceHash;
    auto encodings = encodeViewRegions(
        view, changes.changed, [&](size_t i) { return idsInlineOf[i] != 0; }, context, codec);
    for (size_t i = 0; i < changes.changed.size(); ++i) {
      const uint64_t region = changes.changed[i];
      const bool idsInline = idsInlineOf[i];
      auto& encoded = encodings[i];
      if (!encoded.isOk()) {
        logEvent(
            LogLevel::kError, "encode_failed",
            {{"doc", documentId}, {"codec", regionCodecName(codec)}, {"error", encoded.status().message()}});
        cache.erase(region);
        continue;
      }
      if (idsInline) {
        cache[region] = *encoded;
      } else {
        cache.erase(region);
      }
      delta.regions.push_back({region, *encoded, idsInline});
      ++context.stats.deltaRegions;
      if (!idsInline) ++context.stats.deltaRegionsLayoutIds;
    }
    for (uint64_t region : changes.removed) cache.erase(region);
    delta.removed = changes.removed;
  }
  for (uint64_t region : changes.removed) view.layout.erase(region);
  return deltas;
}

std::vector<std::shared_ptr<const std::string>> snapshotFrames(LodView& view, uint64_t documentId,
                                                               bool resync, const EncodeContext& context,
                                                               size_t partBytes, uint32_t maxFrameBytes,
                                                               RegionCodec codec) {
  // Encoded once per region, codec and version; later subscribers of the
  // codec share the bytes. Those not encoded yet are encoded on several cores.
  auto& cache = view.encoded[codecIndex(codec)];
  std::vector<uint64_t> missing;
  for (const auto& [region, mesh] : view.tessellation->regions()) {
    auto found = cache.find(region);
    if (found == cache.end() || !found->second) missing.push_back(region);
  }
  auto encodings = encodeViewRegions(
      view, missing, [](size_t) { return true; }, context, codec);
  for (size_t i = 0; i < missing.size(); ++i) {
    if (encodings[i].isOk()) {
      cache[missing[i]] = *encodings[i];
    } else {
      logEvent(LogLevel::kError, "encode_failed",
               {{"doc", documentId}, {"error", encodings[i].status().message()}});
    }
  }
  std::vector<std::pair<uint64_t, std::shared_ptr<const std::string>>> regions;
  for (const auto& [region, mesh] : view.tessellation->regions()) {
    auto found = cache.find(region);
    if (found != cache.end() && found->second) regions.emplace_back(region, found->second);
  }
  return encodeSnapshotFrames({documentId, context.version, view.wireProfile, resync, view.surfaceHash},
                              regions, partBytes, maxFrameBytes);
}

}  // namespace tessera::server
