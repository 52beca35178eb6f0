#include "client/lib/document_view.h"

#include <cstring>

#include "core/tessellation/region_merge.h"

namespace tessera::client {

Status DocumentView::apply(const wire::ServerMessage& message) {
  if (message.has_snapshot() && message.snapshot().document_id() == documentId_) {
    const wire::Snapshot& s = message.snapshot();
    for (const wire::Region& r : s.regions()) {
      bytes_ += r.draco().size();
      TESSERA_ASSIGN_OR_RETURN(auto decoded, decodeRegion(r.draco()));
      TESSERA_RETURN_IF_ERROR(adoptIds(decoded.first, decoded.second));
      staging_[r.region_id()] = std::move(decoded.second);
      stagingLayouts_[r.region_id()] = decoded.first.layoutVersion;
    }
    if (s.remaining_parts() == 0) {
      regions_.swap(staging_);
      layouts_.swap(stagingLayouts_);
      staging_.clear();
      stagingLayouts_.clear();
      version_ = s.version();
      ready_ = true;
    }
    return Status::ok();
  }
  if (!message.has_delta() || message.delta().document_id() != documentId_) return Status::ok();
  const wire::Delta& d = message.delta();
  if (!ready_) return Status::ok();  // a resync snapshot is on its way
  if (d.from_version() != version_) {
    ++gaps_;
    ready_ = false;
    return invalidArgument("document " + std::to_string(documentId_) + ": delta " + std::to_string(d.from_version()) +
                           "->" + std::to_string(d.to_version()) + " does not follow version " + std::to_string(version_));
  }
  for (const wire::Region& r : d.regions()) {
    bytes_ += r.draco().size();
    TESSERA_ASSIGN_OR_RETURN(auto decoded, decodeRegion(r.draco()));
    if (Status adopted = adoptIds(decoded.first, decoded.second); !adopted.isOk()) {
      // Ids this view does not hold: as good as a gap, resync.
      ++gaps_;
      ready_ = false;
      return adopted;
    }
    regions_[r.region_id()] = std::move(decoded.second);
    layouts_[r.region_id()] = decoded.first.layoutVersion;
  }
  for (uint64_t id : d.removed_region_ids()) regions_.erase(id), layouts_.erase(id);
  version_ = d.to_version();
  return Status::ok();
}

Status DocumentView::adoptIds(const RegionHeader& header, RegionMesh& decoded) const {
  if (header.idsInline || !header.profile.vertexIds) return Status::ok();
  const auto held = regions_.find(header.regionId);
  if (held == regions_.end()) {
    return invalidArgument("document " + std::to_string(documentId_) + ": region " + std::to_string(header.regionId) +
                           " comes without its ids, and this view does not hold it");
  }
  return adoptLayoutIds(header, decoded, held->second, layouts_.at(header.regionId));
}

int64_t DocumentView::numTriangles() const {
  int64_t n = 0;
  for (const auto& [id, mesh] : regions_) n += static_cast<int64_t>(mesh.triangles.size());
  return n;
}

SurfaceMesh DocumentView::surface() const { return mergeRegions(regions_); }

uint64_t DocumentView::surfaceHash() const {
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  auto mix = [&](const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const auto& [id, mesh] : regions_) {
    mix(&id, sizeof id);
    mix(mesh.vertexIds.data(), mesh.vertexIds.size() * sizeof(uint64_t));
    mix(mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
    mix(mesh.normals.data(), mesh.normals.size() * sizeof(Vec3));
    mix(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  }
  return h;
}

}  // namespace tessera::client
