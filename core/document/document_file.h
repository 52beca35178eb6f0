// The document file format (docs/DOCUMENT_FORMAT.md): versioned, binary,
// little-endian, with a CRC-32 of the payload, so that round trips are exact
// (doubles are stored bit for bit) and corruption, truncation and foreign
// files are detected and named rather than misread.
#pragma once

#include <string>

#include "core/document/document.h"
#include "core/util/status.h"

namespace tessera {

// 1: moves and sharpness tags. 2: also interpolation tags (docs/INTERPOLATION.md,
// edit kind 4). 3: a scheme, and faces of any size (Catmull-Clark). Every
// version up to this one reads; a Loop document is written as version 2.
inline constexpr uint32_t kDocumentFormatVersion = 3;

std::string serializeDocument(const Document& document);
// `source` names the data in error messages (usually the file path).
Expected<Document> deserializeDocument(const std::string& bytes, const std::string& source);

Status saveDocument(const Document& document, const std::string& path);
Expected<Document> loadDocument(const std::string& path);

}  // namespace tessera
