// One filled-in envelope per command and per reply, every field set to a
// value other than its default, so that a round trip exercises every field
// number. schema_test.cc checks that no oneof case is missing here.
// Header-only: the protocol suite compiles *_test.cc files only.
#pragma once

#include <string>
#include <vector>

#include "protocol/tessera.pb.h"

namespace tessera::testing {

// Packed ids as core/hierarchy/ids.h builds them: level << 58 | index.
inline uint64_t packedId(uint64_t level, uint64_t index) {
  return (level << 58) | index;
}

inline void fillProfile(wire::LodProfile* profile) {
  profile->set_base_level(1);
  profile->set_max_level(5);
  profile->set_angle_threshold_degrees(7.5);
  profile->set_triangle_budget(250000);
  profile->set_fidelity(1);
  profile->set_omit_vertex_ids(true);
}

inline void fillSelection(wire::Selection* selection) {
  selection->add_vertex_ids(packedId(3, 1234));
  selection->add_vertex_ids(packedId(3, 1235));
  selection->add_edge_ids(packedId(2, 55));
  selection->add_face_ids(packedId(4, 1023));
}

inline void fillRegion(wire::Region* region, uint64_t id) {
  region->set_region_id(id);
  region->set_draco(std::string("DRACO\x02\x02\x01\x00\xff", 10) + std::to_string(id));
}

inline std::vector<wire::ClientMessage> sampleClientMessages() {
  std::vector<wire::ClientMessage> out;
  auto add = [&out]() -> wire::ClientMessage& {
    out.emplace_back().set_client_seq(out.size());
    return out.back();
  };
  {
    auto* m = add().mutable_hello();
    m->set_protocol_version(1);
    m->set_client_name("viewer on laptop");
    m->set_token("tok-0123456789abcdef");
  }
  add().mutable_list_documents();
  {
    auto* m = add().mutable_create_document();
    m->set_name("bunny");
    m->set_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    m->set_mesh_format(wire::MESH_FORMAT_OBJ);
    m->set_tags("corner 0 inf\n");
    m->set_max_level(6);
    m->set_triangulate(true);
    m->set_crease_method(wire::CREASE_METHOD_CHAIKIN);
    m->set_boundary(wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER);
    m->set_file_name("meshes/bunny.obj");
    m->set_tags_file_name("meshes/bunny.tags");
  }
  {
    auto* m = add().mutable_open_document();
    m->set_document_id(42);
    m->set_token("doc-token");
  }
  add().mutable_close_document()->set_document_id(42);
  add().mutable_delete_document()->set_document_id(43);
  {
    auto* m = add().mutable_subscribe();
    m->set_document_id(42);
    fillProfile(m->mutable_profile());
    m->set_with_commands(true);
  }
  add().mutable_unsubscribe()->set_document_id(42);
  {
    auto* m = add().mutable_move_vertex();
    m->set_document_id(42);
    m->add_vertex_ids(packedId(3, 1234));
    m->add_vertex_ids(packedId(3, 1236));
    m->mutable_target()->set_x(0.25);
    m->mutable_target()->set_y(-1.5);
    m->mutable_target()->set_z(3.0);
    m->set_mode(wire::MOVE_MODE_DIRECT_MANIPULATION);
  }
  {
    auto* m = add().mutable_set_edge_sharpness();
    m->set_document_id(42);
    m->set_edge_id(packedId(2, 55));
    m->set_sharpness(2.5f);
  }
  {
    // The same edit naming the edge by its end vertices.
    auto* m = add().mutable_set_edge_sharpness();
    m->set_document_id(42);
    m->set_edge_id(~uint64_t{0});
    m->add_end_vertex_ids(packedId(2, 7));
    m->add_end_vertex_ids(packedId(2, 31));
    m->set_sharpness(10.0f);
  }
  {
    auto* m = add().mutable_set_vertex_type();
    m->set_document_id(42);
    m->set_vertex_id(packedId(1, 9));
    m->set_type(wire::VERTEX_TYPE_CORNER);
  }
  {
    auto* m = add().mutable_set_interpolation();
    m->set_document_id(42);
    m->set_vertex_id(packedId(1, 9));
    m->set_interpolating(true);
    m->set_tension(2.5);
    m->mutable_tangent()->set_x(1.0);
  }
  {
    auto* m = add().mutable_add_morph_key();
    m->set_document_id(42);
    m->set_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    m->set_mesh_format(wire::MESH_FORMAT_OBJ);
    m->set_file_name("key1.obj");
    m->set_image_from(std::string("\x89PNG\r\n\x1a\n", 8));
    m->set_image_to(std::string("\x89PNG\r\n\x1a\n", 8));
  }
  {
    auto* m = add().mutable_get_morph_control();
    m->set_document_id(42);
    m->set_t(0.25);
    m->set_with_topology(true);
  }
  {
    auto* m = add().mutable_get_cage();
    m->set_document_id(42);
    m->set_level(1);
  }
  {
    // A camera, as a view-dependent subscription and a move of it.
    auto fillView = [](wire::View* v) {
      v->mutable_eye()->set_z(5);
      v->mutable_forward()->set_z(-1);
      v->mutable_up()->set_y(1);
      v->set_fov_y_radians(0.8);
      v->set_near_distance(0.01);
      v->set_width(390);
      v->set_height(844);
      v->set_tolerance_pixels(1);
    };
    auto* s = add().mutable_subscribe();
    s->set_document_id(42);
    s->mutable_profile()->set_triangle_budget(500000);
    fillView(s->mutable_view());
    auto* m = add().mutable_set_view();
    m->set_document_id(42);
    fillView(m->mutable_view());
    m->mutable_view()->set_orthographic(true);
    m->mutable_view()->set_ortho_height(2);
  }
  {
    auto* m = add().mutable_undo();
    m->set_document_id(42);
    m->set_edit_id(17);
  }
  {
    auto* m = add().mutable_redo();
    m->set_document_id(42);
    m->set_edit_id(17);
  }
  {
    auto* m = add().mutable_export_document();
    m->set_document_id(42);
    m->set_level(3);
    m->set_limit(true);
    m->set_draco(true);
  }
  add().mutable_ping();
  add().mutable_stats();
  {
    auto* m = add().mutable_select();
    m->set_document_id(42);
    fillSelection(m->mutable_selection());
  }
  {
    auto* m = add().mutable_grant_token();
    m->set_document_id(42);
    m->set_role(wire::ROLE_EDITOR);
    m->set_token("token-of-sixteen-bytes-at-least");
  }
  {
    auto* m = add().mutable_edit_batch();
    m->set_document_id(42);
    auto* move = m->add_commands()->mutable_move_vertex();
    move->add_vertex_ids(packedId(2, 40));
    move->mutable_target()->set_x(0.5);
    move->set_mode(wire::MOVE_MODE_DIRECT_MANIPULATION);
    auto* crease = m->add_commands()->mutable_set_edge_sharpness();
    crease->set_edge_id(packedId(1, 5));
    crease->set_sharpness(2.0f);
    m->add_commands()->mutable_undo()->set_edit_id(3);
    m->add_commands()->mutable_set_interpolation()->set_vertex_id(packedId(1, 9));
  }
  // The second alternative of SetVertexType's oneof.
  {
    auto* m = add().mutable_set_vertex_type();
    m->set_document_id(42);
    m->set_vertex_id(packedId(0, 3));
    m->set_sharpness(1.25f);
  }
  return out;
}

inline std::vector<wire::ServerMessage> sampleServerMessages() {
  std::vector<wire::ServerMessage> out;
  auto add = [&out]() -> wire::ServerMessage& { return out.emplace_back(); };
  {
    auto* m = add().mutable_hello_ack();
    m->set_client_seq(1);
    m->set_protocol_version(1);
    m->set_server_version("tessera-server 0.1.0");
    m->set_session_id(77);
    m->set_role(wire::ROLE_EDITOR);
    m->set_max_frame_bytes(16u << 20);
  }
  {
    auto* m = add().mutable_ack();
    m->set_client_seq(9);
    m->set_document_id(42);
    m->set_version(18);
    m->set_edit_id(17);
  }
  {
    auto* m = add().mutable_ack();  // of an EditBatch
    m->set_client_seq(11);
    m->set_document_id(42);
    m->set_version(19);
    m->set_edit_id(19);
    m->add_edit_ids(18);
    m->add_edit_ids(19);
  }
  {
    auto* m = add().mutable_reject();
    m->set_client_seq(10);
    m->set_reason(wire::REJECT_REASON_NOT_FOUND);
    m->set_message("document 42: edge e2:999999 does not exist (level 2 has 1920 edges)");
  }
  {
    auto* m = add().mutable_reject();  // of an EditBatch
    m->set_client_seq(12);
    m->set_reason(wire::REJECT_REASON_NOT_FOUND);
    m->set_message("edit batch, command 2 of 3: v9:1: level 9 is above the maximum level 6");
    m->set_batch_index(2);
  }
  {
    auto* m = add().mutable_snapshot();
    m->set_document_id(42);
    m->set_version(18);
    fillProfile(m->mutable_profile());
    fillRegion(m->add_regions(), 1);
    fillRegion(m->add_regions(), 2);
    m->set_remaining_parts(2);
    m->set_resync(true);
  }
  {
    auto* m = add().mutable_delta();
    m->set_document_id(42);
    m->set_from_version(18);
    m->set_to_version(19);
    fillRegion(m->add_regions(), 2);
    m->add_removed_region_ids(5);
    m->set_author_session_id(77);
    m->set_edit_id(18);
    m->set_view_complete(true);
    m->set_view_seq(31);
  }
  {
    auto* m = add().mutable_presence();
    m->set_document_id(42);
    auto* p = m->add_participants();
    p->set_session_id(77);
    p->set_name("alice");
    p->set_role(wire::ROLE_EDITOR);
    fillSelection(p->mutable_selection());
    m->add_participants()->set_name("bob");
  }
  {
    auto* m = add().mutable_error();
    m->set_code(wire::ERROR_CODE_VERSION_MISMATCH);
    m->set_message("client speaks protocol 2, server speaks 1");
    m->set_fatal(true);
  }
  {
    auto* m = add().mutable_document_list();
    m->set_client_seq(2);
    auto* d = m->add_documents();
    d->set_document_id(42);
    d->set_name("bunny");
    d->set_version(18);
    d->set_max_level(6);
  }
  {
    auto* m = add().mutable_export_result();
    m->set_client_seq(14);
    m->set_document_id(42);
    m->set_version(18);
    m->set_glb(std::string("glTF\x02\x00\x00\x00", 8));
  }
  {
    auto* m = add().mutable_morph_control();
    m->set_client_seq(15);
    m->set_document_id(42);
    m->set_version(18);
    m->set_t(0.25);
    for (float x : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) m->add_points(x);
    for (uint32_t v : {0u, 1u, 2u}) m->add_triangles(v);
    m->add_crease_vertices(0);
    m->add_crease_vertices(1);
    m->add_crease_sharpness(10.0f);
    for (float x : {0.0f, 0.0f, 10.0f}) m->add_vertex_sharpness(x);
    m->set_crease_method(wire::CREASE_METHOD_UNIFORM);
    m->set_boundary(wire::BOUNDARY_INTERPOLATION_EDGE_ONLY);
    m->set_max_level(5);
  }
  {
    // A quad and a triangle sharing an edge, at level 1.
    auto* m = add().mutable_cage();
    m->set_client_seq(16);
    m->set_document_id(42);
    m->set_version(18);
    m->set_level(1);
    for (uint32_t n : {4u, 3u}) m->add_face_sizes(n);
    for (uint64_t v : {0u, 1u, 2u, 3u, 2u, 1u, 9u}) m->add_vertices(v);
  }
  {
    auto* m = add().mutable_pong();
    m->set_client_seq(15);
    m->set_server_time_unix_ms(1700000000000);
  }
  {
    auto* m = add().mutable_stats_reply();
    m->set_client_seq(16);
    auto* s = m->add_stats();
    s->set_name("connections");
    s->set_value(3);
    s = m->add_stats();
    s->set_name("edits_per_second");
    s->set_value(12.5);
  }
  {
    auto* m = add().mutable_applied_command();
    m->set_document_id(42);
    m->set_version(19);
    m->set_edit_id(18);
    m->set_author_session_id(77);
    m->set_author_name("alice");
    m->set_server_time_unix_ms(1700000000123);
    auto* move = m->mutable_move_vertex();
    move->set_document_id(42);
    move->add_vertex_ids(packedId(3, 1234));
    move->mutable_target()->set_z(0.01);
    move->set_mode(wire::MOVE_MODE_OFFSET);
  }
  {
    auto* m = add().mutable_applied_command();
    m->set_document_id(42);
    m->set_version(20);
    m->set_edit_id(18);
    m->set_author_session_id(78);
    m->set_author_name("bob");
    m->set_server_time_unix_ms(1700000000456);
    m->mutable_undo()->set_document_id(42);
    m->mutable_undo()->set_edit_id(18);
  }
  {
    auto* m = add().mutable_applied_command();
    m->set_document_id(42);
    m->set_version(21);
    m->set_edit_id(20);
    m->set_author_session_id(77);
    m->set_author_name("alice");
    m->set_server_time_unix_ms(1700000000789);
    auto* batch = m->mutable_edit_batch();
    batch->set_document_id(42);
    batch->add_commands()->mutable_redo()->set_edit_id(18);
    batch->add_commands()->mutable_set_vertex_type()->set_vertex_id(packedId(1, 7));
  }
  {
    auto* m = add().mutable_applied_command();
    m->set_document_id(42);
    m->set_version(22);
    m->set_edit_id(21);
    m->set_author_session_id(78);
    m->set_author_name("bob");
    m->set_server_time_unix_ms(1700000000999);
    auto* tag = m->mutable_set_interpolation();
    tag->set_document_id(42);
    tag->set_vertex_id(packedId(2, 40));
    tag->set_interpolating(true);
    tag->set_tension(0.5);
  }
  {
    auto* m = add().mutable_applied_command();
    m->set_document_id(42);
    m->set_version(23);
    m->set_author_session_id(77);
    m->set_author_name("alice");
    m->set_server_time_unix_ms(1700000001111);
    auto* key = m->mutable_add_morph_key();
    key->set_document_id(42);
    key->set_mesh("v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
    key->set_mesh_format(wire::MESH_FORMAT_OBJ);
  }
  return out;
}

}  // namespace tessera::testing
