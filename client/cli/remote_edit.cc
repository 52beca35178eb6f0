// tessera remote edit: an edit script sent as ONE EditBatch, which the
// server applies whole, as one version, or not at all (docs/PROTOCOL.md,
// EditBatch) -- like `tessera doc edit` on a local file. A refused command
// is reported with its script line; the document is then untouched.
#include <cstdio>

#include "client/cli/remote_commands.h"
#include "client/lib/script_wire.h"
#include "core/document/edit_script.h"
#include "core/util/file_io.h"
#include "protocol/commands.h"

namespace tessera::cli {

namespace {

struct EditArgs {
  std::string document, script;
  uint32_t key = 0;  // a morph document's key every command goes to
};

int runEdit(const ConnectionArgs& connection, const EditArgs& args) {
  auto doc = parseDocumentId(args.document);
  if (!doc.isOk()) return usage("remote edit", doc.status().message());
  // Everything that can be checked here is, before connecting.
  auto text = readFile(args.script);
  if (!text.isOk()) return fail("remote edit", text.status());
  auto commands = parseEditScript(*text, args.script);
  if (!commands.isOk()) return fail("remote edit", commands.status().message());
  if (commands->empty()) {
    std::printf("%s: no commands; nothing sent\n", args.script.c_str());
    return 0;
  }
  if (commands->size() > static_cast<size_t>(kMaxEditBatchCommands)) {
    return fail("remote edit", args.script + ": " + std::to_string(commands->size()) +
                                   " commands, above the server's limit of " +
                                   std::to_string(kMaxEditBatchCommands) +
                                   " per atomic batch; split the script (each part then applies on its own)");
  }
  wire::ClientMessage batch;
  batch.mutable_edit_batch()->set_document_id(*doc);
  for (const ScriptCommand& c : *commands) {
    if (c.kind == ScriptCommand::Kind::kRemove) {
      return fail("remote edit", args.script + ":" + std::to_string(c.line) +
                                     ": remove is local only (use undo); nothing was sent");
    }
    *batch.mutable_edit_batch()->add_commands() = client::editCommandOf(c, args.key);
  }

  auto opened = openDocument(connection, "edit", *doc);
  if (!opened.session) return opened.exitCode;
  client::Session& session = *opened.session;
  auto reply = session.call(batch, 120);
  if (reply.isOk() && reply->has_reject() && reply->reject().batch_index() > 0 &&
      reply->reject().batch_index() <= commands->size()) {
    const ScriptCommand& refused = (*commands)[reply->reject().batch_index() - 1];
    return fail("remote edit", args.script + ":" + std::to_string(refused.line) + ": " +
                                   wire::RejectReason_Name(reply->reject().reason()) + ": " +
                                   reply->reject().message());
  }
  if (int rc = outcome("edit", reply)) return rc;
  const wire::Ack& ack = reply->ack();
  for (size_t i = 0; i < commands->size() && i < static_cast<size_t>(ack.edit_ids_size()); ++i) {
    std::printf("%s:%d: edit %llu\n", args.script.c_str(), (*commands)[i].line,
                static_cast<unsigned long long>(ack.edit_ids(static_cast<int>(i))));
  }
  std::printf("applied %zu commands to document %llu as version %llu\n", commands->size(),
              static_cast<unsigned long long>(*doc), static_cast<unsigned long long>(ack.version()));
  return 0;
}

}  // namespace

void addRemoteEdit(CLI::App& remote, std::shared_ptr<ConnectionArgs> connection, Action& action) {
  CLI::App* edit =
      remote.add_subcommand("edit", "apply an edit script to a document, all or nothing, as one version");
  auto args = std::make_shared<EditArgs>();
  edit->add_option("DOC", args->document, "the document id")->required();
  edit->add_option("--script", args->script, "the edit script (the format of 'tessera doc edit')")
      ->required()
      ->type_name("FILE");
  edit->add_option("--key", args->key, "a morph document's key the script edits: 0 (default) or 1")
      ->type_name("K")
      ->check(CLI::Range(0, 1));
  onChosen(*edit, action, [connection, args] { return runEdit(*connection, *args); });
}

}  // namespace tessera::cli
