#include "client/view/morph_key_follower.h"

#include <utility>

namespace tessera::view {

KeyPositionMap keyPositions(const std::map<uint64_t, RegionMesh>& key0,
                            const std::map<uint64_t, RegionMesh>& key1) {
  KeyPositionMap map;
  const std::map<uint64_t, RegionMesh>* keys[2] = {&key0, &key1};
  for (int k = 0; k < 2; ++k) {
    for (const auto& [id, region] : *keys[k]) {
      for (size_t i = 0; i < region.positions.size() && i < region.vertexIds.size(); ++i) {
        auto& uv = map[region.vertexIds[i]];
        uv[2 * k] = static_cast<float>(region.positions[i][0]);
        uv[2 * k + 1] = static_cast<float>(region.positions[i][1]);
      }
    }
  }
  return map;
}

wire::LodProfile MorphKeyFollower::profileAtKey(const wire::LodProfile& shown, int key) {
  wire::LodProfile atKey = shown;
  atKey.set_base_level(atKey.max_level());
  atKey.set_morph_t(key);
  return atKey;
}

MorphKeyFollower::MorphKeyFollower(uint64_t document,
                                   std::array<std::unique_ptr<client::Session>, 2> sessions)
    : document_(document),
      sessions_(std::move(sessions)),
      views_{client::DocumentView(document), client::DocumentView(document)} {}

MorphKeyFollower::Polled MorphKeyFollower::poll(const wire::LodProfile& shown) {
  Polled polled;
  bool changed = false;
  for (int k = 0; k < 2; ++k) {
    if (!sessions_[k]) continue;
    for (int i = 0; i < 16; ++i) {
      auto m = sessions_[k]->receive(0.001);
      if (!m.isOk()) {
        if (client::isReceiveTimeout(m.status())) break;
        sessions_[k].reset();
        polled.error = "key " + std::to_string(k) + " texture session: " + m.status().message();
        break;
      }
      if (!m->has_snapshot() && !m->has_delta()) continue;
      if (!views_[k].apply(*m).isOk()) {
        // A gap: a fresh snapshot at the same time.
        wire::ClientMessage subscribe;
        subscribe.mutable_subscribe()->set_document_id(document_);
        *subscribe.mutable_subscribe()->mutable_profile() = profileAtKey(shown, k);
        (void)sessions_[k]->send(std::move(subscribe));
        continue;
      }
      changed = true;
    }
  }
  if (changed && views_[0].ready() && views_[1].ready())
    polled.positions =
        std::make_shared<const KeyPositionMap>(keyPositions(views_[0].regions(), views_[1].regions()));
  return polled;
}

}  // namespace tessera::view
