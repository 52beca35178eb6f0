// tessera remote morph-key: makes a document a morph document (docs/PROTOCOL.md §14)
// by sending its second key, a mesh of the same connectivity, and for a 2D
// morph the two images its keys are drawn over (AddMorphKey).
#include <cstdio>

#include "client/cli/remote_commands.h"
#include "core/util/file_io.h"

namespace tessera::cli {

namespace {

struct MorphKeyArgs {
  std::string document, mesh;
  std::vector<std::string> images;  // none, or key 0's and key 1's
};

int runMorphKey(const ConnectionArgs& connection, const MorphKeyArgs& args) {
  auto doc = parseDocumentId(args.document);
  if (!doc.isOk()) return usage("remote morph-key", doc.status().message());
  auto format = meshFormatOf(args.mesh);
  if (!format.isOk()) return usage("remote morph-key", format.status().message());
  auto bytes = readFile(args.mesh);
  if (!bytes.isOk()) return fail("remote morph-key", bytes.status());
  wire::ClientMessage m;
  auto* add = m.mutable_add_morph_key();
  add->set_document_id(*doc);
  add->set_mesh(std::move(*bytes));
  add->set_mesh_format(*format);
  add->set_file_name(args.mesh);
  if (!args.images.empty()) {
    auto from = readFile(args.images[0]);
    if (!from.isOk()) return fail("remote morph-key", from.status());
    auto to = readFile(args.images[1]);
    if (!to.isOk()) return fail("remote morph-key", to.status());
    add->set_image_from(std::move(*from));
    add->set_image_to(std::move(*to));
  }
  auto opened = openDocument(connection, "morph-key", *doc);
  if (!opened.session) return opened.exitCode;
  client::Session& session = *opened.session;
  auto reply = session.call(m, 120);
  if (int rc = outcome("morph-key", reply)) return rc;
  std::printf("document %llu is a morph document (key 1 from %s) at version %llu\n",
              static_cast<unsigned long long>(*doc), args.mesh.c_str(),
              static_cast<unsigned long long>(reply->ack().version()));
  return 0;
}

}  // namespace

void addRemoteMorphKey(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action) {
  CLI::App* sub = remote.add_subcommand(
      "morph-key",
      "add a second key of the same connectivity: the document becomes a morph document (editor)");
  auto args = std::make_shared<MorphKeyArgs>();
  sub->add_option("DOC", args->document, "the document id")->required();
  sub->add_option("MESH", args->mesh, "key 1's base mesh: key 0's triangles, other points")->required();
  sub->add_option("--images", args->images, "a 2D morph: the PNGs under key 0 and key 1")
      ->expected(2)
      ->type_name("A.png B.png");
  onChosen(*sub, action, [connection, args] { return runMorphKey(*connection, *args); });
}

}  // namespace tessera::cli
