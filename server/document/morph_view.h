// A morph view (docs/PROTOCOL.md §14): the LOD view of a morph document at a
// time t, tessellated from KeyedDocument::at(t), the document it follows. A
// morph moves every region, so when either key changes the view is built
// afresh rather than updated; the regions whose surface hash
// (docs/PROTOCOL.md §6.5) is unchanged are not sent again, and the changed
// ones are still encoded once and shared by every subscriber at that t
// (lod_view.h).
#pragma once

#include "core/morph/keyed_document.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"
#include "core/util/status.h"
#include "server/document/lod_view.h"

namespace tessera::server {

// The view of `doc` at `t` for `profile`: its time, the document at that
// time and its tessellation. Fails when the keys do not match or the
// tessellation is over its budget (the error says which).
Expected<LodView> buildMorphView(const KeyedDocument& doc, double t, const LodProfile& profile);

// Rebuilds a morph view of `doc` after a key changed, its regions rehashed
// on `grid`; the regions that differ, all with their ids inline (the
// rebuilt regions have no earlier layout to refer to).
Expected<Tessellation::Changes> rebuildMorphView(const KeyedDocument& doc, LodView& view,
                                                 const QuantizationGrid& grid);

}  // namespace tessera::server
