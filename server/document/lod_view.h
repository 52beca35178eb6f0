// One LOD profile's view of a document: its tessellation, the encodings of
// its regions at the current version, and who holds it
// (docs/ARCHITECTURE.md, "One edit, end to end", steps 4 and 5). After a
// command changed limits, the view's tessellation updates only the regions
// they touch (the invalidation); the view then hashes those regions and
// encodes them once per codec some subscriber decodes (Draco, meshopt:
// docs/REGION_ENCODING.md), one delta per codec that every subscriber of the
// profile with that codec shares; a codec nobody holds costs nothing. A
// subscriber that joins gets the cached encodings of its codec as a snapshot.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"
#include "protocol/tessera.pb.h"
#include "server/base/server_stats.h"
#include "server/document/delta.h"
#include "server/document/subscriber.h"

namespace tessera::server {

struct LodView {
  std::unique_ptr<Tessellation> tessellation;
  // Per codec (RegionCodec's value): region -> its encoding with ids at the
  // host's version; a codec's cache empties when nobody holds it.
  std::array<std::map<uint64_t, std::shared_ptr<const std::string>>, kRegionCodecCount> encoded;
  std::map<uint64_t, uint64_t> layout;                        // region -> its layout version
  std::map<uint64_t, std::weak_ptr<Subscriber>> subscribers;  // session -> subscriber
  std::map<uint64_t, uint64_t> knownVersion;                  // session -> version its snapshot held
  std::map<uint64_t, RegionCodec> codecOf;                    // session -> the codec it decodes
  wire::LodProfile wireProfile;
  // The surface hash (docs/PROTOCOL.md §6.5) of each region as receivers
  // decode it, and their sum, sent in snapshots and deltas; kept per region
  // so an edit costs only the regions it changed.
  std::map<uint64_t, uint64_t> regionHashes;
  uint64_t surfaceHash = 0;
  // A morph view: its time and the document at that time, which the
  // tessellation follows (else it follows key 0).
  std::optional<double> morphT;
  std::unique_ptr<Document> source;
  uint64_t lastUsed = 0;  // DocumentViews' use clock when a subscriber last joined it
};

// How a view's regions are encoded: at which version, on which grid, from
// which document (the view's own source for a morph view, else key 0).
struct EncodeContext {
  uint64_t version = 0;
  const QuantizationGrid& grid;
  const Document& source;
  ServerStats& stats;
};

// A region of the view at `context.version`; without inline ids (a delta
// after a move) it carries its layout's version for receivers holding the
// ids.
Expected<std::shared_ptr<const std::string>> encodeViewRegion(const LodView& view, uint64_t region,
                                                              bool idsInline, const EncodeContext& context,
                                                              RegionCodec codec = RegionCodec::kDraco);

// The codecs the view's live subscribers decode, each once, in RegionCodec
// order.
std::vector<RegionCodec> heldCodecs(const LodView& view);

// The key of a view's delta frame for a codec in a FlushBatch: the view's
// key for Draco (as before there was a second codec), key + "|meshopt".
std::string deltaKey(const std::string& viewKey, RegionCodec codec);

// Updates the view's surface hash for a region that is new or changed, or,
// with `removed`, gone.
void rehashRegion(LodView& view, uint64_t region, const QuantizationGrid& grid, bool removed = false);

// The deltas of what the tessellation's update changed, one per codec in
// heldCodecs: every changed region rehashed once and encoded once per codec
// (those that kept their layout without ids), removed ones forgotten, the
// view's caches brought to `context.version` (a codec nobody holds loses
// its cache). `base` holds the document and versions; each delta's
// regions, removed ids and surface hash are filled here.
std::vector<std::pair<RegionCodec, DeltaContent>> buildDeltas(LodView& view,
                                                              const Tessellation::Changes& changes,
                                                              const EncodeContext& context,
                                                              uint64_t documentId, const DeltaContent& base);

// The view's regions at `context.version` in `codec` as snapshot frames,
// each part at most `partBytes` of regions, encoded once per region, codec
// and version (later subscribers of that codec share the bytes).
std::vector<std::shared_ptr<const std::string>> snapshotFrames(LodView& view, uint64_t documentId,
                                                               bool resync, const EncodeContext& context,
                                                               size_t partBytes, uint32_t maxFrameBytes,
                                                               RegionCodec codec = RegionCodec::kDraco);

}  // namespace tessera::server
