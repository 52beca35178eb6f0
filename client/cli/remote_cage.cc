// tessera remote cage: the polygons of one level of a document's control
// mesh (GetCage, docs/PROTOCOL.md section 17), what a viewer draws as the
// control cage: counted by corners, or listed one face per line.
#include <cstdio>
#include <map>

#include "client/cli/remote_commands.h"
#include "core/hierarchy/ids.h"

namespace tessera::cli {

namespace {

struct CageArgs {
  std::string document;
  int level = 0;
  bool list = false;
};

int runCage(const ConnectionArgs& connection, const CageArgs& args) {
  auto doc = parseDocumentId(args.document);
  if (!doc.isOk()) return usage("remote cage", doc.status().message());
  auto opened = openDocument(connection, "cage", *doc);
  if (!opened.session) return opened.exitCode;
  client::Session& session = *opened.session;
  wire::ClientMessage m;
  m.mutable_get_cage()->set_document_id(*doc);
  m.mutable_get_cage()->set_level(static_cast<uint32_t>(args.level));
  auto reply = session.call(m, 120);
  if (int rc = outcome("cage", reply)) return rc;
  const wire::Cage& cage = reply->cage();
  std::map<uint32_t, size_t> bySize;
  for (uint32_t n : cage.face_sizes()) ++bySize[n];
  std::printf("document %llu, version %llu, level %u: %d faces, %d corners;",
              static_cast<unsigned long long>(cage.document_id()),
              static_cast<unsigned long long>(cage.version()), cage.level(), cage.face_sizes_size(),
              cage.vertices_size());
  for (const auto& [n, count] : bySize) std::printf(" %zu of %u corners", count, n);
  std::printf("\n");
  if (args.list) {
    int at = 0;
    for (uint32_t n : cage.face_sizes()) {
      for (uint32_t k = 0; k < n && at < cage.vertices_size(); ++k, ++at)
        std::printf("%s%s", k ? " " : "",
                    VertexId(static_cast<int>(cage.level()), cage.vertices(at)).toString().c_str());
      std::printf("\n");
    }
  }
  return 0;
}

}  // namespace

void addRemoteCage(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action) {
  CLI::App* sub = remote.add_subcommand("cage", "the polygons of one level of a document's control mesh");
  auto args = std::make_shared<CageArgs>();
  sub->add_option("DOC", args->document, "the document id")->required();
  sub->add_option("--level", args->level, "the level, 0 for the base mesh")->check(wholeNumber());
  sub->add_flag("--list", args->list, "print every face as its vertex ids, one face per line");
  onChosen(*sub, action, [connection, args] { return runCage(*connection, *args); });
}

}  // namespace tessera::cli
