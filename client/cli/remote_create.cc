// tessera remote create: a base mesh becomes a document on the server, with
// the import options of `tessera doc new` (--triangulate, --drop-unused,
// --crease-angle: the server imports, and its Ack says what it changed). The server imports the bytes in
// memory and names the user's file in its errors (CreateDocument.file_name).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "client/cli/mesh_loading.h"
#include "client/cli/remote_commands.h"
#include "core/util/file_io.h"

namespace tessera::cli {

namespace {

struct CreateArgs {
  MeshInputArgs mesh;
  DocumentArgs document;
  std::string documentName;
  std::string scheme;  // empty: the server chooses from the faces
};

int runCreate(const ConnectionArgs& connection, const CreateArgs& given) {
  auto format = meshFormatOf(given.mesh.input);
  if (!format.isOk()) return usage("remote create", format.status().message());
  // The server reads a .usda layer's only Mesh prim: CreateDocument names
  // no prim.
  if (!given.mesh.usdPrim.empty())
    return usage("remote create",
                 "--usd-prim: not available here (the server reads a layer of one Mesh prim; write that "
                 "prim alone, e.g. tessera refine IN --usd-prim PATH --level 0 -o ONE.usda)");
  // A .usda file states its scheme (subdivisionScheme; USD's fallback is
  // catmullClark): it chooses where --scheme does not, as for doc new.
  CreateArgs args = given;
  auto stated = statedSchemeOf(args.mesh);
  if (!stated.isOk()) return fail("remote create", stated.status());
  if (Status s = withFileSubdivisionScheme(args.scheme, !given.scheme.empty(), *stated,
                                           {"loop", "catmull-clark"}, args.mesh.input);
      !s.isOk())
    return usage("remote create", s.message());
  auto bytes = readFile(args.mesh.input);
  if (!bytes.isOk()) return fail("remote create", bytes.status());
  wire::ClientMessage m;
  auto* c = m.mutable_create_document();
  c->set_name(args.documentName.empty() ? std::filesystem::path(args.mesh.input).filename().string()
                                        : args.documentName);
  c->set_mesh(std::move(*bytes));
  c->set_mesh_format(*format);
  c->set_file_name(args.mesh.input);
  c->set_triangulate(args.mesh.triangulate);
  c->set_drop_unused(args.mesh.dropUnused);
  if (args.mesh.creaseAngle >= 0) {
    c->set_crease_by_angle(true);
    c->set_crease_angle(args.mesh.creaseAngle);
  }
  if (!args.mesh.tags.empty()) {
    auto text = readFile(args.mesh.tags);
    if (!text.isOk()) return fail("remote create", text.status());
    c->set_tags(std::move(*text));
    c->set_tags_file_name(args.mesh.tags);
  }
  if (args.scheme == "loop") c->set_scheme(wire::SUBDIVISION_SCHEME_LOOP);
  if (args.scheme == "catmull-clark") c->set_scheme(wire::SUBDIVISION_SCHEME_CATMULL_CLARK);
  if (args.document.maxLevel >= 0) c->set_max_level(static_cast<uint32_t>(args.document.maxLevel));
  const LoopOptions loop = loopOptions(args.document.scheme);
  c->set_crease_method(loop.creaseMethod == CreaseMethod::kChaikin ? wire::CREASE_METHOD_CHAIKIN
                                                                   : wire::CREASE_METHOD_UNIFORM);
  c->set_boundary(loop.boundary == BoundaryInterpolation::kEdgeAndCorner
                      ? wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER
                      : wire::BOUNDARY_INTERPOLATION_EDGE_ONLY);
  auto session = connectTo(connection);
  if (!session.isOk()) return connectFailed("create", session.status());
  auto reply = (*session)->call(m, 120);
  if (int rc = outcome("create", reply)) return rc;
  // What the server's import did, said as `tessera doc new` says it.
  ImportReport report;
  report.renumbering.dropped = static_cast<int>(reply->ack().dropped_vertices());
  report.edgesCreasedByAngle = static_cast<int>(reply->ack().creased_edges());
  const std::string note = describeImport(report, importOptions(args.mesh));
  if (!note.empty())
    std::fprintf(stderr, "tessera remote create: %s: %s\n", args.mesh.input.c_str(), note.c_str());
  if (args.scheme.empty() && reply->ack().scheme() == wire::SUBDIVISION_SCHEME_CATMULL_CLARK) {
    std::fprintf(stderr,
                 "tessera remote create: %s: faces that are not triangles: a catmull-clark document "
                 "(--scheme loop --triangulate for Loop's triangles)\n",
                 args.mesh.input.c_str());
  }
  std::printf("%llu\n", static_cast<unsigned long long>(reply->ack().document_id()));
  return 0;
}

}  // namespace

void addRemoteCreate(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action) {
  CLI::App* create =
      remote.add_subcommand("create", "import a base mesh as a new document (admin); prints its id");
  auto args = std::make_shared<CreateArgs>();
  addMeshInputOptions(*create, args->mesh);
  addDocumentOptions(*create, args->document);
  addDocumentSchemeOption(*create, args->scheme);
  create->add_option("--doc-name", args->documentName, "the document's name (default: the file's name)")
      ->type_name("NAME");
  onChosen(*create, action, [connection, args] { return runCreate(*connection, *args); });
}

}  // namespace tessera::cli
