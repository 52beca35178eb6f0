// tessera doc edit (doc_edit.cc): an edit script applied to a local document
// under the server's acceptance rule.
#pragma once

#include <string>

namespace tessera::cli {

struct DocEditArgs {
  std::string document;  // rewritten in place
  std::string script;
  bool each = false;  // line by line: refused lines are reported and skipped
};

int runDocEdit(const DocEditArgs& args);

}  // namespace tessera::cli
