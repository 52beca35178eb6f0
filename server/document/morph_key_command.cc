#include "server/document/morph_key_command.h"

#include <string>

#include "core/io/mesh_import.h"
#include "core/loop/level_builder.h"
#include "core/morph/morph.h"
#include "server/document/mesh_format.h"

namespace tessera::server {

namespace {

// Each image of a 2D morph: far above a sample's, far below the frame limit.
constexpr size_t kMaxMorphImageBytes = 16u << 20;

bool isPng(const std::string& bytes) {
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  return bytes.compare(0, kSignature.size(), kSignature) == 0;
}

}  // namespace

Status applyAddMorphKey(KeyedDocument& keyed, store::DocumentId id, const wire::AddMorphKey& request,
                        JournalEntry& entry) {
  const std::string doc = "document " + std::to_string(id.value);
  if (keyed.isMorph()) return invalidArgument("add morph key: " + doc + " already has two keys");
  // Refused before the mesh is read: no work for a key that cannot be added.
  TESSERA_RETURN_IF_ERROR(checkMorphScheme(keyed.key0(), "add morph key: key 0 (" + doc + ")"));
  const char* extension = meshExtensionOf(request.mesh_format());
  if (extension == nullptr) return invalidArgument("add morph key: mesh_format is not set");
  for (const auto* image : {&request.image_from(), &request.image_to()}) {
    const char* which = image == &request.image_from() ? "image_from" : "image_to";
    if (image->size() > kMaxMorphImageBytes) {
      return invalidArgument("add morph key: " + std::string(which) + " has " +
                             std::to_string(image->size()) + " bytes, above the limit of " +
                             std::to_string(kMaxMorphImageBytes));
    }
    if (!image->empty() && !isPng(*image))
      return invalidArgument("add morph key: " + std::string(which) + " is not a PNG");
  }
  if (request.image_from().empty() != request.image_to().empty()) {
    return invalidArgument("add morph key: send both images or neither");
  }
  const std::string name = request.file_name().empty() ? "the second key's mesh" : request.file_name();
  TESSERA_ASSIGN_OR_RETURN(ImportedMesh imported,
                           importMeshFromBytesWithReport(request.mesh(), extension, name, ImportOptions{}));
  TESSERA_RETURN_IF_ERROR(checkSameConnectivity(
      keyed.key0().baseTopology(), BaseTopology::fromBaseMesh(imported.mesh), "key 0 (" + doc + ")", name));
  entry.kind = JournalEntry::Kind::kAddKey;
  entry.keyPoints = imported.mesh.positions();
  entry.images = {request.image_from(), request.image_to()};
  return keyed.addKey(entry.keyPoints, entry.images);
}

}  // namespace tessera::server
