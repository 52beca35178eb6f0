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
#include "core/render/dynamic_refinement.h"

namespace tessera::view {

struct DrawOptions {
  Mat4 view{}, projection{};
  bool wireframe = false;
  bool regionColours = false;
  bool matcap = false;
  // Control vertices: their world diameter (controlPointDiameter) and the
  // pixels one world unit covers at depth 1 (viewport height / (2 tan(fovy / 2))).
  float pointDiameter = 0.01f;
  float pixelsPerUnit = 600;
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

  // Uploads new and changed regions and frees removed ones.
  void sync(const RegionMap& regions);
  // Client-side refinement: draws refined[i] for the i-th region of
  // `regions` (in map order), uploaded every frame as a stream (seed 002
  // keeps nothing between frames); a later sync() uploads the received
  // regions again.
  void stream(const RegionMap& regions, const std::vector<RefinedMesh>& refined);
  void drawSurface(const DrawOptions& options);
  // Points are drawn over the surface; callers pass only the visible ones.
  void drawPoints(const std::vector<V3>& points, const PointStyle& style, const DrawOptions& options);

  int64_t triangles() const { return triangles_; }
  size_t regionCount() const { return regions_.size(); }
  uint64_t uploads() const { return uploads_; }

 private:
  struct GpuRegion {
    std::shared_ptr<const RegionMesh> mesh;  // what was uploaded
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei indices = 0;
    std::array<float, 3> colour{};
  };
  Renderer() = default;
  static void release(GpuRegion& r);
  // Frees the regions not in `regions`.
  void evict(const RegionMap& regions);
  // The region's GL objects, created on first use.
  GpuRegion& slot(uint64_t id);
  void upload(GpuRegion& r, std::span<const Vec3> positions, std::span<const Vec3> normals,
              std::span<const std::array<int, 3>> triangles, GLenum usage);

  GLuint meshProgram_ = 0, pointProgram_ = 0;
  GLuint pointVao_ = 0, pointVbo_ = 0;
  std::map<uint64_t, GpuRegion> regions_;
  int64_t triangles_ = 0;
  uint64_t uploads_ = 0;
};

}  // namespace tessera::view
