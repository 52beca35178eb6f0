#include "core/document/document_scheme.h"

namespace tessera {

const char* documentSchemeName(DocumentScheme scheme) {
  return scheme == DocumentScheme::kLoop ? "loop" : "catmull-clark";
}

Expected<DocumentScheme> parseDocumentScheme(const std::string& name) {
  if (name == "loop") return DocumentScheme::kLoop;
  if (name == "catmull-clark") return DocumentScheme::kCatmullClark;
  return invalidArgument("unknown document scheme '" + name + "' (loop or catmull-clark)");
}

}  // namespace tessera
