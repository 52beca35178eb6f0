// A document's subdivision scheme, chosen when it is created and kept in its
// file (docs/DOCUMENT_FORMAT.md): Loop on triangles, or Catmull-Clark on any
// polygons (docs/ARCHITECTURE.md "The forest on Catmull-Clark").
#pragma once

#include <cstdint>
#include <string>

#include "core/util/status.h"

namespace tessera {

enum class DocumentScheme : uint8_t { kLoop = 0, kCatmullClark = 1 };

// "loop" or "catmull-clark", the names the CLI and the protocol use.
const char* documentSchemeName(DocumentScheme scheme);
Expected<DocumentScheme> parseDocumentScheme(const std::string& name);

}  // namespace tessera
