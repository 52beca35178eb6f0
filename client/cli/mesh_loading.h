// The options that name a base mesh and how it becomes a document, shared by
// `info`, `refine`, `doc new` and `remote create` so that they read alike:
//   IN [--tags FILE] [--triangulate] [--drop-unused] [--crease-angle DEG]
//                                                    (every mesh input)
//   [--max-level N] [--crease-method M] [--boundary B]   (documents)
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera::cli {

struct MeshInputArgs {
  std::string input;
  std::string tags;  // empty: none
  bool triangulate = false;
  bool dropUnused = false;
  double creaseAngle = -1;  // degrees; negative: not given
  std::string usdPrim;      // .usda: the Mesh prim, by path or name; empty: the only one
  std::string command;      // "refine", "doc new": names the command in notes
};

struct SchemeArgs {
  std::string creaseMethod;  // empty: the default (uniform)
  std::string boundary;      // empty: the default (edge-only)
};

struct DocumentArgs {
  SchemeArgs scheme;
  int maxLevel = -1;  // -1: not given
};

// IN (required), --tags FILE, --triangulate, --drop-unused, --crease-angle DEG,
// --usd-prim PATH.
void addMeshInputOptions(CLI::App& app, MeshInputArgs& args);
// Of the import options, those given on `app`'s command line that a
// polygon reader, which reads a file's polygons as they are, does not apply
// (--triangulate, --drop-unused, --crease-angle).
std::vector<std::string> givenTriangleImportOptions(const CLI::App& app);
// --scheme S: loop or catmull-clark; left empty when not given (the scheme
// then follows the faces).
void addDocumentSchemeOption(CLI::App& app, std::string& scheme);
// --crease-method M, --boundary B.
void addSchemeOptions(CLI::App& app, SchemeArgs& args);
// The scheme options and --max-level N.
void addDocumentOptions(CLI::App& app, DocumentArgs& args);

LoopOptions loopOptions(const SchemeArgs& args);
// `maxLevelDefault` when --max-level is not given.
DocumentOptions documentOptions(const DocumentArgs& args, int maxLevelDefault = DocumentOptions{}.maxLevel);

ImportOptions importOptions(const MeshInputArgs& args);

// Reads, validates and tags the mesh; errors name the file (and its line).
// What the import changed (vertices dropped, edges creased by angle) is
// said on stderr: "tessera refine: bunny.ply: dropped 1 unused vertex
// (--drop-unused)".
// `report`, when given, receives what the import did (and the options the
// file states, for withFileScheme).
Expected<BaseMesh> loadMesh(const MeshInputArgs& args, ImportReport* report = nullptr);
// The same on the polygons of `args.input`, already read (importPolygonSoup).
Expected<BaseMesh> loadMeshFromSoup(const MeshInputArgs& args, PolygonSoup soup, ImportReport* report);

// The scheme options a mesh file states (OBJ's `t interpolateboundary`,
// `t creasemethod`) where the command line gives none; a command line
// that says otherwise is refused, naming both (`file` names the mesh).
Status withFileScheme(SchemeArgs& args, const std::string& boundary, const std::string& creaseMethod,
                      const std::string& file);

// The subdivision scheme a mesh file states (USD's subdivisionScheme, read
// into PolygonSoup::scheme) where the command line gives none (`given`
// false); a command line that says otherwise is refused, naming both.
// "none" and an empty statement leave `scheme` as it is; `accepted` lists
// the schemes the command can take from a file.
Status withFileSubdivisionScheme(std::string& scheme, bool given, const std::string& stated,
                                 const std::vector<std::string>& accepted, const std::string& file);

// The scheme a .usda file's chosen Mesh prim states (empty for other
// formats, which cannot say), read ahead of the command's own import.
Expected<std::string> statedSchemeOf(const MeshInputArgs& args);

}  // namespace tessera::cli
