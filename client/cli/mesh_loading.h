// The options that name a base mesh and how it becomes a document, shared by
// `info`, `refine`, `doc new` and `remote create` so that they read alike:
//   IN [--tags FILE] [--triangulate]                 (every mesh input)
//   [--max-level N] [--crease-method M] [--boundary B]   (documents)
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "core/document/document.h"
#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera::cli {

struct MeshInputArgs {
  std::string input;
  std::string tags;  // empty: none
  bool triangulate = false;
};

struct SchemeArgs {
  std::string creaseMethod;  // empty: the default (uniform)
  std::string boundary;      // empty: the default (edge-only)
};

struct DocumentArgs {
  SchemeArgs scheme;
  int maxLevel = -1;  // -1: not given
};

// IN (required), --tags FILE, --triangulate.
void addMeshInputOptions(CLI::App& app, MeshInputArgs& args);
// --crease-method M, --boundary B.
void addSchemeOptions(CLI::App& app, SchemeArgs& args);
// The scheme options and --max-level N.
void addDocumentOptions(CLI::App& app, DocumentArgs& args);

LoopOptions loopOptions(const SchemeArgs& args);
// `maxLevelDefault` when --max-level is not given.
DocumentOptions documentOptions(const DocumentArgs& args, int maxLevelDefault = DocumentOptions{}.maxLevel);

// Reads, validates and tags the mesh; errors name the file (and its line).
Expected<BaseMesh> loadMesh(const MeshInputArgs& args);

}  // namespace tessera::cli
