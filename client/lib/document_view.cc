#include "client/lib/document_view.h"

#include <cstdio>
#include <cstring>

#include "core/tessellation/region_merge.h"
#include "core/tessellation/surface_hash.h"
#include "core/view/tile_assembly.h"
#include "core/view/tile_tree.h"

namespace tessera::client {

Status DocumentView::apply(const wire::ServerMessage& message) {
  if (message.has_snapshot() && message.snapshot().document_id() == documentId_) {
    const wire::Snapshot& s = message.snapshot();
    for (const wire::Region& r : s.regions()) {
      bytes_ += r.draco().size();
      TESSERA_ASSIGN_OR_RETURN(auto decoded, decodeRegion(r.draco()));
      ++regionsByCodec_[static_cast<size_t>(decoded.first.codec)];
      TESSERA_RETURN_IF_ERROR(adoptIds(decoded.first, decoded.second));
      staging_[r.region_id()] = std::move(decoded.second);
      stagingLayouts_[r.region_id()] = decoded.first.layoutVersion;
    }
    if (s.remaining_parts() == 0) {
      regions_.swap(staging_);
      layouts_.swap(stagingLayouts_);
      staging_.clear();
      stagingLayouts_.clear();
      regionHashes_.clear();
      boundaries_.clear();
      version_ = s.version();
      announced_ = s.surface_hash();
      ready_ = true;
      viewComplete_ = false;
      viewSeq_ = 0;
    }
    return Status::ok();
  }
  if (!message.has_delta() || message.delta().document_id() != documentId_) return Status::ok();
  const wire::Delta& d = message.delta();
  if (!ready_) return Status::ok();  // a resync snapshot is on its way
  if (d.from_version() != version_) {
    ++gaps_;
    ready_ = false;
    return invalidArgument("document " + std::to_string(documentId_) + ": delta " +
                           std::to_string(d.from_version()) + "->" + std::to_string(d.to_version()) +
                           " does not follow version " + std::to_string(version_));
  }
  for (const wire::Region& r : d.regions()) {
    bytes_ += r.draco().size();
    TESSERA_ASSIGN_OR_RETURN(auto decoded, decodeRegion(r.draco()));
    ++regionsByCodec_[static_cast<size_t>(decoded.first.codec)];
    if (Status adopted = adoptIds(decoded.first, decoded.second); !adopted.isOk()) {
      // Ids this view does not hold: as good as a gap, resync.
      ++gaps_;
      ready_ = false;
      return adopted;
    }
    regions_[r.region_id()] = std::move(decoded.second);
    layouts_[r.region_id()] = decoded.first.layoutVersion;
    forgetDerived(r.region_id());
  }
  for (uint64_t id : d.removed_region_ids()) regions_.erase(id), layouts_.erase(id), forgetDerived(id);
  version_ = d.to_version();
  announced_ = d.surface_hash();
  viewComplete_ = d.view_complete();
  viewSeq_ = d.view_seq();
  return Status::ok();
}

Status DocumentView::adoptIds(const RegionHeader& header, RegionMesh& decoded) const {
  if (header.idsInline || !header.profile.vertexIds) return Status::ok();
  const auto held = regions_.find(header.regionId);
  if (held == regions_.end()) {
    return invalidArgument("document " + std::to_string(documentId_) + ": region " +
                           std::to_string(header.regionId) +
                           " comes without its ids, and this view does not hold it");
  }
  return adoptLayoutIds(header, decoded, held->second, layouts_.at(header.regionId));
}

int64_t DocumentView::numTriangles() const {
  int64_t n = 0;
  for (const auto& [id, mesh] : regions_) n += static_cast<int64_t>(mesh.triangles.size());
  return n;
}

SurfaceMesh DocumentView::surface() const {
  return mergeRegions(regions_);
}

std::map<uint64_t, std::vector<Vec3>> DocumentView::closedTilePositions(int64_t* moved) const {
  if (auto preview = regions_.find(TileKey::preview().regionId()); preview != regions_.end()) {
    if (moved) *moved = 0;
    return {{preview->first, preview->second.positions}};
  }
  std::vector<const RegionMesh*> meshes;
  std::vector<const TileBoundary*> boundaries;
  for (const auto& [id, mesh] : regions_) {
    auto [it, fresh] = boundaries_.try_emplace(id);
    if (fresh) it->second = tileBoundary(mesh);
    meshes.push_back(&mesh);
    boundaries.push_back(&it->second);
  }
  std::vector<std::vector<Vec3>> closed = closeCracks(meshes, boundaries, moved);
  std::map<uint64_t, std::vector<Vec3>> out;
  size_t i = 0;
  for (const auto& [id, mesh] : regions_) out.emplace(id, std::move(closed[i++]));
  return out;
}

void DocumentView::forgetDerived(uint64_t region) const {
  regionHashes_.erase(region);
  boundaries_.erase(region);
}

uint64_t DocumentView::surfaceHash() const {
  uint64_t sum = 0;
  for (const auto& [id, mesh] : regions_) {
    auto [it, fresh] = regionHashes_.try_emplace(id, 0);
    if (fresh) it->second = regionSurfaceHash(mesh);
    sum += it->second;
  }
  return sum;
}

Status DocumentView::verifySurface() const {
  if (announced_ == 0) return Status::ok();
  const uint64_t held = surfaceHash();
  if (held == announced_) return Status::ok();
  char text[96];
  std::snprintf(text, sizeof text, "surface hash %016llx, the server's %016llx",
                static_cast<unsigned long long>(held), static_cast<unsigned long long>(announced_));
  return internalError("document " + std::to_string(documentId_) + " at version " + std::to_string(version_) +
                       ": the assembled regions differ from the server's: " + text);
}

}  // namespace tessera::client
