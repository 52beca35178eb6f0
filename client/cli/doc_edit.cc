// tessera doc edit: an edit script applied to a local document file under the
// same rule a server applies, the document's bounds
// (core/tessellation/document_bounds.h), so that a session recorded on a
// server and replayed here accepts and refuses the same commands.
//
// All or nothing by default, like `tessera remote edit`. With --each every
// line is its own command, as a server takes commands one by one: a refused
// line is reported and leaves the document as it was, and the others apply.
#include "client/cli/doc_edit.h"

#include <cstdio>

#include "client/cli/command_line.h"
#include "core/document/document_file.h"
#include "core/document/edit_script.h"
#include "core/tessellation/document_bounds.h"
#include "core/tessellation/document_grid.h"
#include "core/util/file_io.h"

namespace tessera::cli {

int runDocEdit(const DocEditArgs& args) {
  auto doc = loadDocument(args.document);
  if (!doc.isOk()) return fail("doc edit", doc.status());
  auto grid = documentGrid(*doc);
  if (!grid.isOk()) return fail("doc edit", grid.status().withContext(args.document));
  auto text = readFile(args.script);
  if (!text.isOk()) return fail("doc edit", text.status());
  auto commands = parseEditScript(*text, args.script);
  if (!commands.isOk()) return fail("doc edit", commands.status());

  Document working = *doc;  // all or nothing, unless --each
  int applied = 0, refused = 0;
  for (const ScriptCommand& c : *commands) {
    Status status = applyWithinBounds(c, working, *grid);
    const std::string where = args.script + ":" + std::to_string(c.line) + ": ";
    if (status.code() == ErrorCode::kInternal) return fail("doc edit", where + status.message());
    if (!status.isOk() && !args.each)
      return fail("doc edit", Status(status.code(), where + status.message()));
    if (!status.isOk()) {
      ++refused;
      std::printf("%srefused: %s\n", where.c_str(), status.message().c_str());
      continue;
    }
    ++applied;
    if (args.each) std::printf("%saccepted\n", where.c_str());
  }
  Status saved = saveDocument(working, args.document);
  if (!saved.isOk()) return fail("doc edit", saved);
  std::printf("applied %d commands", applied);
  if (args.each) std::printf(", refused %d", refused);
  std::printf("; %zu edits in %s\n", working.edits().size(), args.document.c_str());
  return 0;
}

}  // namespace tessera::cli
