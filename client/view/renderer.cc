#include "client/view/renderer.h"

#include "client/view/shaders.h"
#include "core/view/tile_tree.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace tessera::view {

namespace {

using namespace shaders;

Expected<GLuint> compile(GLenum type, const char* source) {
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    return internalError(std::string("shader does not compile: ") + log);
  }
  return shader;
}

Expected<GLuint> link(const char* vertex, const char* fragment) {
  TESSERA_ASSIGN_OR_RETURN(GLuint vs, compile(GL_VERTEX_SHADER, vertex));
  auto fs = compile(GL_FRAGMENT_SHADER, fragment);
  if (!fs.isOk()) {
    glDeleteShader(vs);
    return fs.status();
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, *fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(*fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    return internalError(std::string("shader program does not link: ") + log);
  }
  return program;
}

// Levels 0 to 8 from cool to warm, the same in every viewer.
std::array<float, 3> levelColour(int level) {
  static constexpr std::array<std::array<float, 3>, 9> kLevels{{{0.25f, 0.35f, 0.85f},
                                                                {0.20f, 0.60f, 0.90f},
                                                                {0.20f, 0.78f, 0.70f},
                                                                {0.35f, 0.80f, 0.35f},
                                                                {0.75f, 0.82f, 0.25f},
                                                                {0.95f, 0.70f, 0.20f},
                                                                {0.95f, 0.45f, 0.20f},
                                                                {0.90f, 0.25f, 0.25f},
                                                                {0.85f, 0.25f, 0.65f}}};
  return kLevels[static_cast<size_t>(std::clamp(level, 0, 8))];
}

// A stable, well-spread colour for a region id.
std::array<float, 3> regionColour(uint64_t id) {
  uint64_t h = id * 0x9E3779B97F4A7C15ull;
  h ^= h >> 31;
  const float hue = static_cast<float>(h % 360) / 60.0f;
  const float x = 1 - std::abs(std::fmod(hue, 2.0f) - 1);
  std::array<float, 3> c{};
  switch (static_cast<int>(hue)) {
    case 0:
      c = {1, x, 0};
      break;
    case 1:
      c = {x, 1, 0};
      break;
    case 2:
      c = {0, 1, x};
      break;
    case 3:
      c = {0, x, 1};
      break;
    case 4:
      c = {x, 0, 1};
      break;
    default:
      c = {1, 0, x};
      break;
  }
  for (float& v : c) v = 0.35f + 0.55f * v;
  return c;
}

void setMatrices(GLuint program, const DrawOptions& o) {
  glUniformMatrix4fv(glGetUniformLocation(program, "uView"), 1, GL_FALSE, o.view.data());
  glUniformMatrix4fv(glGetUniformLocation(program, "uProjection"), 1, GL_FALSE, o.projection.data());
}

}  // namespace

Expected<std::unique_ptr<Renderer>> Renderer::create() {
  std::unique_ptr<Renderer> r(new Renderer());
  TESSERA_ASSIGN_OR_RETURN(r->meshProgram_, link(kMeshVertex, kMeshFragment));
  TESSERA_ASSIGN_OR_RETURN(r->pointProgram_, link(kPointVertex, kPointFragment));
  TESSERA_ASSIGN_OR_RETURN(r->lineProgram_, link(kLineVertex, kLineFragment));
  glGenVertexArrays(1, &r->pointVao_);
  glGenBuffers(1, &r->pointVbo_);
  glBindVertexArray(r->pointVao_);
  glBindBuffer(GL_ARRAY_BUFFER, r->pointVbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindVertexArray(0);
  return r;
}

Renderer::~Renderer() {
  for (auto& [id, r] : regions_) release(r);
  glDeleteBuffers(1, &pointVbo_);
  glDeleteVertexArrays(1, &pointVao_);
  glDeleteProgram(meshProgram_);
  glDeleteProgram(pointProgram_);
  glDeleteProgram(lineProgram_);
  glDeleteTextures(2, textures_);
}

void Renderer::release(GpuRegion& r) {
  glDeleteBuffers(1, &r.vbo);
  glDeleteBuffers(1, &r.ibo);
  glDeleteBuffers(1, &r.uvbo);
  glDeleteVertexArrays(1, &r.vao);
  r = {};
}

void Renderer::evict(const RegionMap& regions) {
  for (auto it = regions_.begin(); it != regions_.end();) {
    if (regions.count(it->first)) {
      ++it;
      continue;
    }
    triangles_ -= it->second.indices / 3;
    release(it->second);
    it = regions_.erase(it);
  }
}

Renderer::GpuRegion& Renderer::slot(uint64_t id) {
  GpuRegion& r = regions_[id];
  if (r.vao == 0) {
    glGenVertexArrays(1, &r.vao);
    glGenBuffers(1, &r.vbo);
    glGenBuffers(1, &r.ibo);
    glGenBuffers(1, &r.uvbo);
    r.colour = regionColour(id);
    // The surface's preview (docs/VIEWS.md "The first picture") is level-0 points.
    r.levelColour = levelColour(std::max(TileKey::fromRegionId(id).level, 0));
  }
  return r;
}

void Renderer::upload(GpuRegion& r, std::span<const Vec3> positions, std::span<const Vec3> normals,
                      std::span<const std::array<int, 3>> triangles, GLenum usage) {
  triangles_ -= r.indices / 3;
  std::vector<float> vertices;
  vertices.reserve(positions.size() * 6);
  for (size_t v = 0; v < positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) vertices.push_back(static_cast<float>(positions[v][k]));
    for (int k = 0; k < 3; ++k) vertices.push_back(static_cast<float>(normals[v][k]));
  }
  std::vector<uint32_t> indices;
  indices.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<uint32_t>(t[k]));
  glBindVertexArray(r.vao);
  // Texture coordinates belong to the received mesh (uploadKeyUv): until
  // they are uploaded for this one, the attribute is off (it reads 0).
  glDisableVertexAttribArray(2);
  r.uvFrom = nullptr;
  glBindBuffer(GL_ARRAY_BUFFER, r.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
               usage);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r.ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)),
               indices.data(), usage);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glBindVertexArray(0);
  r.indices = static_cast<GLsizei>(indices.size());
  triangles_ += r.indices / 3;
  ++uploads_;
}

void Renderer::sync(const RegionMap& regions, const std::shared_ptr<const KeyPositionMap>& keyPositions) {
  evict(regions);
  for (const auto& [id, mesh] : regions) {
    GpuRegion& r = slot(id);
    if (r.mesh != mesh) {
      r.mesh = mesh;
      r.uvFrom = nullptr;
      upload(r, mesh->positions, mesh->normals, mesh->triangles, GL_STATIC_DRAW);
    }
    if (keyPositions && r.uvFrom != keyPositions.get()) uploadKeyUv(r, *keyPositions);
  }
}

void Renderer::uploadKeyUv(GpuRegion& r, const KeyPositionMap& keyPositions) {
  const RegionMesh& mesh = *r.mesh;
  std::vector<float> uv;
  uv.reserve(mesh.positions.size() * 4);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    std::array<float, 4> at{
        static_cast<float>(mesh.positions[v][0]), static_cast<float>(mesh.positions[v][1]),
        static_cast<float>(mesh.positions[v][0]), static_cast<float>(mesh.positions[v][1])};
    if (v < mesh.vertexIds.size()) {
      auto it = keyPositions.find(mesh.vertexIds[v]);
      if (it != keyPositions.end()) at = it->second;
    }
    // Pixel centres: pixel (i, j) covers [i, i + 1) x [j, j + 1), so a mesh
    // in pixel coordinates maps x to x / width. Rows run top to bottom in
    // the texture as in the image.
    uv.push_back(at[0] / imageSize_[0][0]);
    uv.push_back(at[1] / imageSize_[0][1]);
    uv.push_back(at[2] / imageSize_[1][0]);
    uv.push_back(at[3] / imageSize_[1][1]);
  }
  glBindVertexArray(r.vao);
  glBindBuffer(GL_ARRAY_BUFFER, r.uvbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(uv.size() * sizeof(float)), uv.data(),
               GL_STATIC_DRAW);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glBindVertexArray(0);
  r.uvFrom = &keyPositions;
}

void Renderer::setMorphImages(const Image& from, const Image& to) {
  if (textures_[0] == 0) glGenTextures(2, textures_);
  const Image* images[2] = {&from, &to};
  for (int k = 0; k < 2; ++k) {
    glBindTexture(GL_TEXTURE_2D, textures_[k]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, images[k]->width, images[k]->height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, images[k]->rgba.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    imageSize_[k][0] = static_cast<float>(images[k]->width);
    imageSize_[k][1] = static_cast<float>(images[k]->height);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  for (auto& [id, r] : regions_) r.uvFrom = nullptr;  // sizes changed
}

void Renderer::stream(const RegionMap& regions, const std::vector<RefinedMesh>& refined) {
  evict(regions);
  size_t i = 0;
  for (const auto& [id, mesh] : regions) {
    if (i >= refined.size()) break;
    GpuRegion& r = slot(id);
    r.mesh = nullptr;  // what is on the GPU is not the received mesh
    const RefinedMesh& m = refined[i++];
    upload(r, m.positions, m.normals, m.triangles, GL_STREAM_DRAW);
  }
}

void Renderer::drawSurface(const DrawOptions& o) {
  glEnable(GL_DEPTH_TEST);
  glUseProgram(meshProgram_);
  setMatrices(meshProgram_, o);
  const GLint colour = glGetUniformLocation(meshProgram_, "uColour");
  const GLint flat = glGetUniformLocation(meshProgram_, "uFlat");
  glUniform1i(glGetUniformLocation(meshProgram_, "uMatcap"), o.matcap ? 1 : 0);
  // World +Y in view space, for the hemisphere light.
  const std::array<float, 3> up{o.view[4], o.view[5], o.view[6]};
  glUniform3fv(glGetUniformLocation(meshProgram_, "uUp"), 1, up.data());
  // Push the filled surface back a little so the wireframe lies on top.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glUniform1i(flat, 0);
  const bool textured = textures_[0] != 0 && !o.regionColours && !o.levelColours;
  glUniform1i(glGetUniformLocation(meshProgram_, "uTextured"), textured ? 1 : 0);
  if (textured) {
    for (int k = 0; k < 2; ++k) {
      glActiveTexture(GL_TEXTURE0 + k);
      glBindTexture(GL_TEXTURE_2D, textures_[k]);
    }
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(meshProgram_, "uFrom"), 0);
    glUniform1i(glGetUniformLocation(meshProgram_, "uTo"), 1);
    glUniform1f(glGetUniformLocation(meshProgram_, "uT"), o.morphT);
  }
  for (const auto& [id, r] : regions_) {
    const std::array<float, 3> c = o.levelColours    ? r.levelColour
                                   : o.regionColours ? r.colour
                                                     : std::array<float, 3>{0.72f, 0.74f, 0.78f};
    glUniform3fv(colour, 1, c.data());
    glBindVertexArray(r.vao);
    glDrawElements(GL_TRIANGLES, r.indices, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glUniform1i(glGetUniformLocation(meshProgram_, "uTextured"), 0);
  if (o.wireframe) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glUniform1i(flat, 1);
    const std::array<float, 3> line{0.1f, 0.12f, 0.16f};
    glUniform3fv(colour, 1, line.data());
    for (const auto& [id, r] : regions_) {
      glBindVertexArray(r.vao);
      glDrawElements(GL_TRIANGLES, r.indices, GL_UNSIGNED_INT, nullptr);
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glBindVertexArray(0);
}

void Renderer::drawPoints(const std::vector<V3>& points, const PointStyle& style, const DrawOptions& o) {
  if (points.empty()) return;
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glUseProgram(pointProgram_);
  setMatrices(pointProgram_, o);
  glUniform3fv(glGetUniformLocation(pointProgram_, "uColour"), 1, style.colour.data());
  glUniform1f(glGetUniformLocation(pointProgram_, "uDiameter"), o.pointDiameter * style.scale);
  glUniform1f(glGetUniformLocation(pointProgram_, "uPixelsPerUnit"), o.pixelsPerUnit);
  glUniform2f(glGetUniformLocation(pointProgram_, "uPixelRange"), style.minPixels, style.maxPixels);
  glBindVertexArray(pointVao_);
  glBindBuffer(GL_ARRAY_BUFFER, pointVbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(V3)), points.data(),
               GL_STREAM_DRAW);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
}

void Renderer::drawLines(const std::vector<V3>& ends, std::array<float, 3> colour, const DrawOptions& o) {
  if (ends.size() < 2) return;
  glDisable(GL_DEPTH_TEST);
  glUseProgram(lineProgram_);
  setMatrices(lineProgram_, o);
  glUniform3fv(glGetUniformLocation(lineProgram_, "uColour"), 1, colour.data());
  glBindVertexArray(pointVao_);
  glBindBuffer(GL_ARRAY_BUFFER, pointVbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ends.size() * sizeof(V3)), ends.data(),
               GL_STREAM_DRAW);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(ends.size() / 2 * 2));
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace tessera::view
