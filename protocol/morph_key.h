// The morph key an edit command is on (PROTOCOL.md section 14): the `key`
// field of MoveVertex, SetEdgeSharpness, SetVertexType, SetInterpolation,
// Undo and Redo. One reading and one writing for every message whose oneof
// holds those commands under those names (ClientMessage, EditCommand,
// AppliedCommand); any other command is on key 0.
#pragma once

#include <cstdint>

namespace tessera {

template <typename Command>
uint32_t morphKeyOf(const Command& c) {
  if (c.has_move_vertex()) return c.move_vertex().key();
  if (c.has_set_edge_sharpness()) return c.set_edge_sharpness().key();
  if (c.has_set_vertex_type()) return c.set_vertex_type().key();
  if (c.has_set_interpolation()) return c.set_interpolation().key();
  if (c.has_undo()) return c.undo().key();
  if (c.has_redo()) return c.redo().key();
  return 0;
}

template <typename Command>
void setMorphKey(Command& c, uint32_t key) {
  if (c.has_move_vertex()) c.mutable_move_vertex()->set_key(key);
  if (c.has_set_edge_sharpness()) c.mutable_set_edge_sharpness()->set_key(key);
  if (c.has_set_vertex_type()) c.mutable_set_vertex_type()->set_key(key);
  if (c.has_set_interpolation()) c.mutable_set_interpolation()->set_key(key);
  if (c.has_undo()) c.mutable_undo()->set_key(key);
  if (c.has_redo()) c.mutable_redo()->set_key(key);
}

}  // namespace tessera
