// Small builders for client messages in the integration tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "protocol/tessera.pb.h"

namespace tessera::testing {

inline std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline wire::ClientMessage createDocument(const std::string& name, const std::string& obj,
                                          const std::string& tags, int maxLevel) {
  wire::ClientMessage m;
  auto* c = m.mutable_create_document();
  c->set_name(name);
  c->set_mesh(obj);
  c->set_mesh_format(wire::MESH_FORMAT_OBJ);
  c->set_tags(tags);
  c->set_max_level(static_cast<uint32_t>(maxLevel));
  return m;
}

inline wire::ClientMessage grant(uint64_t doc, wire::Role role, const std::string& token) {
  wire::ClientMessage m;
  m.mutable_grant_token()->set_document_id(doc);
  m.mutable_grant_token()->set_role(role);
  m.mutable_grant_token()->set_token(token);
  return m;
}

inline wire::ClientMessage openDocument(uint64_t doc) {
  wire::ClientMessage m;
  m.mutable_open_document()->set_document_id(doc);
  return m;
}

inline wire::ClientMessage subscribe(uint64_t doc, uint32_t base, uint32_t max, double angle = 15) {
  wire::ClientMessage m;
  m.mutable_subscribe()->set_document_id(doc);
  auto* p = m.mutable_subscribe()->mutable_profile();
  p->set_base_level(base);
  p->set_max_level(max);
  p->set_angle_threshold_degrees(angle);
  return m;
}

inline wire::ClientMessage moveVertex(uint64_t doc, uint64_t packedVertex, double x, double y, double z,
                                      wire::MoveMode mode = wire::MOVE_MODE_DIRECT_MANIPULATION) {
  wire::ClientMessage m;
  auto* v = m.mutable_move_vertex();
  v->set_document_id(doc);
  v->add_vertex_ids(packedVertex);
  v->mutable_target()->set_x(x);
  v->mutable_target()->set_y(y);
  v->mutable_target()->set_z(z);
  v->set_mode(mode);
  return m;
}

inline wire::ClientMessage ping() {
  wire::ClientMessage m;
  m.mutable_ping();
  return m;
}

}  // namespace tessera::testing
