// tessera info: what a base mesh is made of, before anyone refines it.
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include "client/cli/commands.h"
#include "client/cli/human_format.h"
#include "client/cli/mesh_loading.h"

namespace tessera::cli {

namespace {

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

int runInfo(const MeshInputArgs& args) {
  auto mesh = loadMesh(args);
  if (!mesh.isOk()) return fail("info", mesh.status());
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

  std::printf("file            %s\n", args.input.c_str());
  std::printf("vertices        %s\n", formatCount(mesh->numVertices()).c_str());
  std::printf("faces           %s\n", formatCount(mesh->numFaces()).c_str());
  std::printf("edges           %s\n", formatCount(mesh->numEdges()).c_str());
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

}  // namespace

void addInfoCommand(CLI::App& app, Action& action) {
  CLI::App* info = app.add_subcommand("info", "describe a base mesh");
  info->footer(
      "Prints vertex, face and edge counts, the valence histogram, boundary loops,\n"
      "connected components, genus, feature-tag counts and the bounding box.");
  auto args = std::make_shared<MeshInputArgs>();
  addMeshInputOptions(*info, *args);
  onChosen(*info, action, [args] { return runInfo(*args); });
}

}  // namespace tessera::cli
