// Saving a KeyedDocument (docs/DOCUMENT_FORMAT.md, "Morph documents"). A
// document of one key is saved exactly as a plain document file, so every
// existing store and file stays readable and nothing changes for it; one
// with two keys is a container of both document files and the images.
#pragma once

#include <string>

#include "core/morph/keyed_document.h"
#include "core/util/status.h"

namespace tessera {

std::string serializeKeyedDocument(const KeyedDocument& document);
// Either form; `source` names the data in error messages.
Expected<KeyedDocument> deserializeKeyedDocument(const std::string& bytes, const std::string& source);

}  // namespace tessera
