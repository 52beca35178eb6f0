// The parts of the _tessera extension module: each function adds one
// purpose's classes and functions (module.cc calls them in order: a class
// is bound before the functions that return it).
#pragma once

#include <pybind11/pybind11.h>

#include "client/python/remote_session.h"

namespace tessera::python {

namespace py = pybind11;

using SessionClass = py::class_<RemoteSession, std::shared_ptr<RemoteSession>>;

void bindErrors(py::module_& m);                                // errors.cc
void bindElementIds(py::module_& m);                            // element_ids.cc
void bindOffline(py::module_& m);                               // offline_bindings.cc
void bindViews(py::module_& m);                                 // view_bindings.cc
SessionClass bindSession(py::module_& m);                       // session_bindings.cc
void bindDocumentCommands(SessionClass& session);               // document_commands.cc
void bindEditCommands(SessionClass& session);                   // edit_commands.cc
void bindMorphCommands(py::module_& m, SessionClass& session);  // morph_commands.cc
void bindSubscriptions(SessionClass& session);                  // view_bindings.cc

}  // namespace tessera::python
