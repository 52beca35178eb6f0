// A view-dependent subscriber's cameras (docs/PROTOCOL.md section 16): what
// the server does with a Subscribe's or a SetView's View before and after
// checking it. Input: up to 8 wire Views, each prefixed by one length byte.
// Each is parsed (bytes that are no View are skipped) and checked
// (server/document/view_request.h: a refusal must name its reason); a view
// that passes selects tiles on a creased cube of max level 6, one catalogue
// for the whole input as a server keeps one per document. Every selection
// must cover each base face exactly once, every visible tile must be within
// its (possibly raised) tolerance or at the deepest level, and the tiles'
// cracks must close without error.
#include <cmath>
#include <map>
#include <string>

#include "core/view/tile_assembly.h"
#include "core/view/tile_selection.h"
#include "fuzz_support.h"
#include "server/document/view_request.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  constexpr int kLevel = 6;
  Document doc = cubeDocument(kLevel);
  TileCatalogue catalogue(doc);
  size_t at = 0;
  for (int views = 0; views < 8 && at < size; ++views) {
    const size_t length = std::min<size_t>(data[at], size - at - 1);
    wire::View wireView;
    const bool parsed = wireView.ParseFromArray(data + at + 1, static_cast<int>(length));
    at += 1 + length;
    if (!parsed) continue;
    auto view = server::viewFromWire(wireView);
    if (!view.isOk()) {
      checkError(view.status(), "viewFromWire");
      require(view.status().message().rfind("view: ", 0) == 0,
              "a refused view's message does not start 'view: '");
      continue;
    }
    const int64_t budget = (views % 3 == 0) ? 20000 : 0;
    auto selection = selectTiles(*view, catalogue, budget);
    if (!selection.isOk()) {
      checkError(selection.status(), "selectTiles");
      continue;
    }
    std::map<uint64_t, double> area;
    std::vector<const RegionMesh*> meshes;
    for (const SelectedTile& t : selection->tiles) {
      auto mesh = catalogue.mesh(t.key);
      require(mesh.isOk(), "a selected tile has no mesh");
      meshes.push_back(*mesh);
      for (const FaceId& f : catalogue.tree().facesShown(t.key))
        area[f.index() >> (2 * f.level())] += std::ldexp(1.0, -2 * f.level());
      if (t.visible && t.key.level < kLevel)
        require(t.projectedError <= selection->tolerancePixels, "a visible tile is over the tolerance");
    }
    require(area.size() == doc.counts().faces(0), "the tiles do not cover every base face");
    for (const auto& [face, a] : area)
      require(std::abs(a - 1.0) < 1e-9, "a base face is covered twice or in part");
    const auto closed = closeCracks(meshes);
    require(closed.size() == meshes.size(), "crack closing lost a tile");
  }
  return 0;
}
