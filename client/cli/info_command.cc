// tessera info: what a base mesh is made of, before anyone refines it.
#include <cstdio>
#include <map>
#include <vector>

#include "client/cli/arguments.h"
#include "client/cli/commands.h"
#include "client/cli/mesh_loading.h"

namespace tessera::cli {

namespace {

constexpr const char* kHelp =
    "usage: tessera info IN [--tags FILE] [--triangulate]\n"
    "\n"
    "Prints vertex, face and edge counts, the valence histogram, boundary\n"
    "loops, connected components, genus, feature-tag counts and the bounding box.\n"
    "\n"
    "  IN             .obj .off .ply .stl .gltf .glb\n"
    "  --tags FILE    feature tags: 'crease I J S' and 'corner I S' lines (docs/FORMATS.md)\n"
    "  --triangulate  fan polygons with more than three corners\n";

int countBoundaryLoops(const TriMesh& mesh) {
  std::vector<char> seen(mesh.n_halfedges(), 0);
  int loops = 0;
  for (auto heh : mesh.halfedges()) {
    if (!mesh.is_boundary(heh) || seen[heh.idx()]) continue;
    ++loops;
    for (auto h = heh; !seen[h.idx()]; h = mesh.next_halfedge_handle(h)) seen[h.idx()] = 1;
  }
  return loops;
}

int countComponents(const TriMesh& mesh) {
  std::vector<int> component(mesh.n_vertices(), -1);
  int count = 0;
  std::vector<OpenMesh::VertexHandle> stack;
  for (auto start : mesh.vertices()) {
    if (component[start.idx()] >= 0) continue;
    stack.push_back(start);
    component[start.idx()] = count;
    while (!stack.empty()) {
      auto v = stack.back();
      stack.pop_back();
      for (auto w : mesh.vv_range(v)) {
        if (component[w.idx()] < 0) {
          component[w.idx()] = count;
          stack.push_back(w);
        }
      }
    }
    ++count;
  }
  return count;
}

}  // namespace

int runInfo(const std::vector<std::string>& rawArgs) {
  ArgumentSpec spec{{"--triangulate"}, {"--tags"}};
  auto args = parseArguments(rawArgs, spec);
  if (!args.isOk()) {
    std::fprintf(stderr, "tessera info: %s\n\n%s", args.status().message().c_str(), kHelp);
    return 2;
  }
  if (args->has("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (args->positional.size() != 1) {
    std::fprintf(stderr, "tessera info: expected one input mesh\n\n%s", kHelp);
    return 2;
  }
  const std::string& input = args->positional[0];
  auto mesh = loadMesh(input, args->option("--tags"), args->has("--triangulate"));
  if (!mesh.isOk()) {
    std::fprintf(stderr, "tessera info: %s\n", mesh.status().toString().c_str());
    return 1;
  }
  const TriMesh& m = mesh->mesh();
  std::map<int, int> valences;
  for (auto v : m.vertices()) ++valences[static_cast<int>(m.valence(v))];
  const int loops = countBoundaryLoops(m);
  const int components = countComponents(m);
  const int euler = mesh->numVertices() - mesh->numEdges() + mesh->numFaces();
  // Per component, V - E + F = 2 - 2g - b; summed over all of them:
  const int genus = (2 * components - loops - euler) / 2;
  const auto tags = mesh->tagCounts();
  const auto box = mesh->boundingBox();

  std::printf("file            %s\n", input.c_str());
  std::printf("vertices        %d\n", mesh->numVertices());
  std::printf("faces           %d\n", mesh->numFaces());
  std::printf("edges           %d\n", mesh->numEdges());
  std::printf("valence         ");
  for (const auto& [valence, count] : valences) std::printf("%d:%d ", valence, count);
  std::printf("\n");
  std::printf("boundary loops  %d\n", loops);
  std::printf("components      %d\n", components);
  std::printf("euler           %d\n", euler);
  std::printf("genus           %d\n", genus);
  std::printf("creases         %d infinite, %d semi-sharp\n", tags.infiniteCreases, tags.semiSharpCreases);
  std::printf("sharp vertices  %d\n", tags.sharpVertices);
  std::printf("bbox min        %.9g %.9g %.9g\n", box.min[0], box.min[1], box.min[2]);
  std::printf("bbox max        %.9g %.9g %.9g\n", box.max[0], box.max[1], box.max[2]);
  std::printf("bbox diagonal   %.9g\n", box.diagonal());
  return 0;
}

}  // namespace tessera::cli
