// tessera remote: talk to a tessera-server through the client library --
// list, create, grant, run an edit script, export, stats.
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>

#include "client/cli/commands.h"
#include "client/cli/human_format.h"
#include "client/cli/remote_commands.h"
#include "client/cli/remote_session.h"

namespace tessera::cli {

namespace {

int runList(const ConnectionArgs& connection) {
  auto session = connectTo(connection);
  if (!session.isOk()) return connectFailed("list", session.status());
  wire::ClientMessage m;
  m.mutable_list_documents();
  auto reply = (*session)->call(m, 30);
  if (int rc = outcome("list", reply)) return rc;
  for (const auto& d : reply->document_list().documents()) {
    std::printf("%llu\t%s\tversion %llu\n", static_cast<unsigned long long>(d.document_id()),
                d.name().c_str(), static_cast<unsigned long long>(d.version()));
  }
  if (reply->document_list().documents_size() == 0 && connection.token.empty() &&
      connection.tokenFile.empty()) {
    std::fprintf(stderr,
                 "tessera remote list: no documents: a session without a token sees none "
                 "(give --token or --token-file)\n");
  }
  return 0;
}

struct GrantArgs {
  std::string document, role, token;
};

int runGrant(const ConnectionArgs& connection, const GrantArgs& args) {
  uint64_t doc = 0;
  if (args.document != "all") {
    auto parsed = parseDocumentId(args.document);
    if (!parsed.isOk()) return usage("remote grant", parsed.status().message() + " or 'all'");
    doc = *parsed;
  }
  const std::map<std::string, wire::Role> roles = {
      {"viewer", wire::ROLE_VIEWER}, {"editor", wire::ROLE_EDITOR}, {"admin", wire::ROLE_ADMIN}};
  auto session = connectTo(connection);
  if (!session.isOk()) return connectFailed("grant", session.status());
  wire::ClientMessage m;
  m.mutable_grant_token()->set_document_id(doc);
  m.mutable_grant_token()->set_role(roles.at(args.role));
  m.mutable_grant_token()->set_token(args.token);
  return outcome("grant", (*session)->call(m, 30));
}

struct ExportArgs {
  std::string document, output;
  int level = 0;
  bool limit = false, draco = false;
};

int runExport(const ConnectionArgs& connection, const ExportArgs& args) {
  auto doc = parseDocumentId(args.document);
  if (!doc.isOk()) return usage("remote export", doc.status().message());
  auto opened = openDocument(connection, "export", *doc);
  if (!opened.session) return opened.exitCode;
  client::Session& session = *opened.session;
  wire::ClientMessage m;
  m.mutable_export_document()->set_document_id(*doc);
  m.mutable_export_document()->set_level(static_cast<uint32_t>(args.level));
  m.mutable_export_document()->set_limit(args.limit);
  m.mutable_export_document()->set_draco(args.draco);
  auto reply = session.call(m, 120);
  if (int rc = outcome("export", reply)) return rc;
  std::ofstream out(args.output, std::ios::binary);
  out << reply->export_result().glb();
  out.close();
  if (!out) return fail("remote export", args.output + ": cannot write the GLB");
  std::printf("wrote %s: %s (version %llu)\n", args.output.c_str(),
              formatBytes(static_cast<double>(reply->export_result().glb().size())).c_str(),
              static_cast<unsigned long long>(reply->export_result().version()));
  return 0;
}

int runStats(const ConnectionArgs& connection) {
  auto session = connectTo(connection);
  if (!session.isOk()) return connectFailed("stats", session.status());
  wire::ClientMessage m;
  m.mutable_stats();
  auto reply = (*session)->call(m, 30);
  if (int rc = outcome("stats", reply)) return rc;
  for (const auto& stat : reply->stats_reply().stats()) {
    std::printf("%-26s %s\n", stat.name().c_str(), formatStat(stat.name(), stat.value()).c_str());
  }
  return 0;
}

}  // namespace

void addRemoteCommand(CLI::App& app, Action& action) {
  CLI::App* remote = app.add_subcommand("remote", "talk to a tessera-server");
  remote->require_subcommand(1);
  auto connection = std::make_shared<ConnectionArgs>();
  addConnectionOptions(*remote, *connection);

  CLI::App* list = remote->add_subcommand("list", "documents this token may read");
  onChosen(*list, action, [connection] { return runList(*connection); });

  addRemoteCreate(*remote, connection, action);

  CLI::App* grant = remote->add_subcommand("grant", "let TOKEN act on a document, or on all of them (admin)");
  auto grantArgs = std::make_shared<GrantArgs>();
  grant->add_option("DOC", grantArgs->document, "a document id, or 'all'")->required();
  grant->add_option("ROLE", grantArgs->role, "viewer, editor or admin")
      ->required()
      ->check(oneOf({"viewer", "editor", "admin"}));
  grant->add_option("TOKEN", grantArgs->token, "the token to grant the role")->required();
  onChosen(*grant, action, [connection, grantArgs] { return runGrant(*connection, *grantArgs); });

  addRemoteEdit(*remote, connection, action);
  addRemoteMorphKey(*remote, connection, action);
  addRemoteCage(*remote, connection, action);

  CLI::App* exporter = remote->add_subcommand("export", "write a document's surface at a level as GLB");
  auto exportArgs = std::make_shared<ExportArgs>();
  exporter->add_option("DOC", exportArgs->document, "the document id")->required();
  exporter->add_option("--level", exportArgs->level, "uniform level to write")
      ->required()
      ->check(wholeNumber());
  exporter->add_option("-o,--output", exportArgs->output, "the .glb to write")->required()->type_name("OUT");
  exporter->add_flag("--limit", exportArgs->limit, "limit positions and normals instead of control points");
  exporter->add_flag("--draco", exportArgs->draco, "compress with KHR_draco_mesh_compression");
  onChosen(*exporter, action, [connection, exportArgs] { return runExport(*connection, *exportArgs); });

  CLI::App* stats = remote->add_subcommand("stats", "the server's counters");
  onChosen(*stats, action, [connection] { return runStats(*connection); });

  // The connection options may also follow the command ("remote list --port 7878").
  for (CLI::App* sub : remote->get_subcommands([](CLI::App*) { return true; })) sub->fallthrough();
  remote->footer(
      "Scripts for 'remote edit' use the format of 'tessera doc edit' (move, offset, crease, corner,\n"
      "undo, redo); the server applies a whole script or none of it, as one version.");
}

}  // namespace tessera::cli
