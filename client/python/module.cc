// The _tessera extension module that the pure-Python package `tessera`
// wraps (client/python/tessera/__init__.py, docs/PYTHON.md).
#include "client/python/bindings.h"
#include "client/python/replies.h"

PYBIND11_MODULE(_tessera, m) {
  using namespace tessera::python;
  m.doc() =
      "Tessera's client library and core for Python: sessions with tessera-server\n"
      "(commands, subscriptions, regions as NumPy arrays) and offline refinement.\n"
      "Import the package `tessera`, not this module.";
  bindErrors(m);
  bindElementIds(m);
  bindReplies(m);
  bindOffline(m);
  bindViews(m);
  SessionClass session = bindSession(m);
  bindDocumentCommands(session);
  bindEditCommands(session);
  bindMorphCommands(m, session);
  bindSubscriptions(session);
}
