// Renderer: the GPU side of tessera-view. One vertex buffer and one index
// buffer per region, re-uploaded only when the region's mesh pointer changes;
// smooth shading with the limit normals under key, fill and sky light or a
// matcap (shaders.h), an optional wireframe overlay and per-region colours;
// control vertices as round points sized in world units.
// Needs a current OpenGL 3.3 core context for its whole life.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "client/view/connection.h"
#include "client/view/control_points.h"
#include "client/view/gl.h"
#include "client/view/view_math.h"
#include "core/io/png_image.h"
#include "core/render/dynamic_refinement.h"

namespace tessera::view {

struct DrawOptions {
  Mat4 view{}, projection{};
  bool wireframe = false;
  bool regionColours = false;
  bool levelColours = false;  // tiles of a view (region ids are tile ids): one colour per level
  bool matcap = false;
  // Control vertices: their world diameter (controlPointDiameter) and the
  // pixels one world unit covers at depth 1 (viewport height / (2 tan(fovy / 2))).
  float pointDiameter = 0.01f;
  float pixelsPerUnit = 600;
  // A 2D morph with images (setMorphImages): the time shown, for the
  // cross-dissolve; textured unless the region colours are on.
  float morphT = 0;
};

struct PointStyle {
  std::array<float, 3> colour{1.0f, 0.85f, 0.1f};
  float scale = 1;  // times DrawOptions::pointDiameter
  float minPixels = 3, maxPixels = 14;
};

class Renderer {
 public:
  static Expected<std::unique_ptr<Renderer>> create();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads new and changed regions and frees removed ones; with key
  // positions (a 2D morph's, connection.h), also their texture coordinates,
  // again for every region when the map is another.
  void sync(const RegionMap& regions, const std::shared_ptr<const KeyPositionMap>& keyPositions = nullptr);
  // A 2D morph document's images (RGBA, rows top to bottom): the surface is
  // drawn with them from then on.
  void setMorphImages(const Image& from, const Image& to);
  // Client-side refinement: draws refined[i] for the i-th region of
  // `regions` (in map order), uploaded every frame as a stream (nothing is
  // kept between frames, docs/VIEWER.md "Client-side refinement"); a later
  // sync() uploads the received regions again.
  void stream(const RegionMap& regions, const std::vector<RefinedMesh>& refined);
  void drawSurface(const DrawOptions& options);
  // Points are drawn over the surface; callers pass only the visible ones.
  void drawPoints(const std::vector<V3>& points, const PointStyle& style, const DrawOptions& options);
  // Line segments (two points each) in one colour, over the surface like the
  // points: callers pass only the visible ones (control_cage.h).
  void drawLines(const std::vector<V3>& segmentEnds, std::array<float, 3> colour, const DrawOptions& options);

  int64_t triangles() const { return triangles_; }
  size_t regionCount() const { return regions_.size(); }
  uint64_t uploads() const { return uploads_; }

 private:
  struct GpuRegion {
    std::shared_ptr<const RegionMesh> mesh;  // what was uploaded
    GLuint vao = 0, vbo = 0, ibo = 0, uvbo = 0;
    const KeyPositionMap* uvFrom = nullptr;  // the key positions its texture coordinates came from
    GLsizei indices = 0;
    std::array<float, 3> colour{}, levelColour{};
  };
  Renderer() = default;
  static void release(GpuRegion& r);
  // Frees the regions not in `regions`.
  void evict(const RegionMap& regions);
  // The region's GL objects, created on first use.
  GpuRegion& slot(uint64_t id);
  void upload(GpuRegion& r, std::span<const Vec3> positions, std::span<const Vec3> normals,
              std::span<const std::array<int, 3>> triangles, GLenum usage);

  // Texture coordinates of the region's vertices: by vertex id, each key's
  // position over its image's size; a vertex no key view has (another
  // profile) uses its own position for both.
  void uploadKeyUv(GpuRegion& r, const KeyPositionMap& keyPositions);

  GLuint meshProgram_ = 0, pointProgram_ = 0;
  GLuint textures_[2] = {0, 0};
  float imageSize_[2][2] = {{1, 1}, {1, 1}};
  GLuint lineProgram_ = 0;  // plain colour; shares the points' buffer
  GLuint pointVao_ = 0, pointVbo_ = 0;
  std::map<uint64_t, GpuRegion> regions_;
  int64_t triangles_ = 0;
  uint64_t uploads_ = 0;
};

}  // namespace tessera::view
