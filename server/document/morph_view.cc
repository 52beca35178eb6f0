#include "server/document/morph_view.h"

#include <map>
#include <memory>
#include <utility>

namespace tessera::server {

Expected<LodView> buildMorphView(const KeyedDocument& doc, double t, const LodProfile& profile) {
  LodView view;
  view.morphT = t;
  TESSERA_ASSIGN_OR_RETURN(Document at, doc.at(t));
  view.source = std::make_unique<Document>(std::move(at));
  TESSERA_ASSIGN_OR_RETURN(Tessellation tessellation, Tessellation::build(*view.source, profile));
  view.tessellation = std::make_unique<Tessellation>(std::move(tessellation));
  return view;
}

Expected<Tessellation::Changes> rebuildMorphView(const KeyedDocument& doc, LodView& view,
                                                 const QuantizationGrid& grid) {
  TESSERA_ASSIGN_OR_RETURN(LodView fresh, buildMorphView(doc, *view.morphT, view.tessellation->profile()));
  const std::map<uint64_t, uint64_t> before = std::move(view.regionHashes);
  view.tessellation = std::move(fresh.tessellation);
  view.source = std::move(fresh.source);
  view.regionHashes.clear();
  view.surfaceHash = 0;
  Tessellation::Changes changes;
  for (const auto& [region, mesh] : view.tessellation->regions()) {
    rehashRegion(view, region, grid);
    auto old = before.find(region);
    if (old == before.end() || old->second != view.regionHashes[region]) changes.changed.push_back(region);
  }
  for (const auto& [region, hash] : before) {
    if (!view.tessellation->regions().count(region)) changes.removed.push_back(region);
  }
  changes.relaid = changes.changed;
  changes.rebuilt = true;
  // rehashRegion above counted the new regions; the flush's buildDelta
  // rehashes the changed ones again, which leaves the same sums.
  return changes;
}

}  // namespace tessera::server
