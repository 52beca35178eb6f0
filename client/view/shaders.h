// The GLSL 3.30 core shaders of tessera-view's renderer.
#pragma once

namespace tessera::view::shaders {

inline constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aKeyUv;  // a 2D morph's: texture coordinates in key 0's and key 1's image
uniform mat4 uView;
uniform mat4 uProjection;
out vec3 vNormal;
out vec3 vPosition;
out vec4 vKeyUv;
void main() {
  vKeyUv = aKeyUv;
  vec4 p = uView * vec4(aPosition, 1.0);
  vPosition = p.xyz;
  vNormal = mat3(uView) * aNormal;  // the view matrix is a rotation and a translation
  gl_Position = uProjection * p;
}
)";

// Three lights, as a photographer would set them, fixed to the camera so that
// whatever side the user looks at is lit:
// - a warm key light from the upper left, in front, with a specular highlight;
// - a cool fill light from the right, at a third of the key, so the sides the
//   key misses are not black;
// - a hemisphere ambient: sky colour on normals facing the world's up, ground
//   colour on those facing down (uUp is world +Y in view space), so tops and
//   undersides read differently even where neither light reaches.
// The matcap (uMatcap) instead takes the colour from the view-space normal
// alone, as a studio-lit clay sphere would show it: a procedural matcap, no
// image needed. Two-sided: back faces use the flipped normal.
// A 2D morph document (uTextured) shows its images instead, unlit: each
// point takes key 0's image where it was under key 0 and key 1's where it
// was under key 1, cross-dissolved by t (docs/VIEWER.md, "Morph
// documents").
inline constexpr const char* kMeshFragment = R"(#version 330 core
in vec3 vNormal;
in vec3 vPosition;
uniform vec3 uColour;
uniform vec3 uUp;
uniform int uFlat;
uniform int uMatcap;
uniform int uTextured;
uniform sampler2D uFrom;
uniform sampler2D uTo;
uniform float uT;
in vec4 vKeyUv;
out vec4 fragColour;

const vec3 kKey = normalize(vec3(-0.45, 0.75, 0.55));
const vec3 kFill = normalize(vec3(0.75, 0.05, 0.55));

vec3 lit(vec3 n, vec3 toEye) {
  float h = 0.5 + 0.5 * dot(n, uUp);
  vec3 ambient = mix(vec3(0.16, 0.15, 0.15), vec3(0.36, 0.39, 0.45), h);
  float key = max(dot(n, kKey), 0.0);
  float fill = max(dot(n, kFill), 0.0);
  vec3 halfway = normalize(kKey + toEye);
  float specular = key > 0.0 ? pow(max(dot(n, halfway), 0.0), 48.0) : 0.0;
  vec3 light = ambient + key * vec3(0.70, 0.67, 0.62) + fill * vec3(0.24, 0.27, 0.32);
  return uColour * light + vec3(0.16 * specular);
}

vec3 matcap(vec3 n) {
  float up = 0.5 + 0.5 * n.y;
  vec3 clay = mix(vec3(0.30, 0.24, 0.22), vec3(0.88, 0.80, 0.73), up);
  float facing = max(n.z, 0.0);
  float rim = pow(1.0 - facing, 3.0);
  float highlight = pow(max(dot(n, normalize(vec3(-0.35, 0.5, 0.8))), 0.0), 40.0);
  vec3 c = clay * (0.55 + 0.45 * facing) + rim * vec3(0.22, 0.26, 0.32) + vec3(0.55 * highlight);
  return c * (uColour / vec3(0.72, 0.74, 0.78));
}

void main() {
  if (uFlat != 0) { fragColour = vec4(uColour, 1.0); return; }
  if (uTextured != 0) {
    fragColour = vec4(mix(texture(uFrom, vKeyUv.xy).rgb, texture(uTo, vKeyUv.zw).rgb, uT), 1.0);
    return;
  }
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 toEye = normalize(-vPosition);
  fragColour = vec4(uMatcap != 0 ? matcap(n) : lit(n, toEye), 1.0);
}
)";

// Control vertices: a world-space diameter, so that dots shrink with the
// distance like the model does; kept between a few pixels and a bound.
inline constexpr const char* kPointVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uView;
uniform mat4 uProjection;
uniform float uDiameter;        // world units
uniform float uPixelsPerUnit;   // at depth 1: viewport height / (2 tan(fovy / 2))
uniform vec2 uPixelRange;
void main() {
  vec4 p = uView * vec4(aPosition, 1.0);
  gl_Position = uProjection * p;
  gl_PointSize = clamp(uDiameter * uPixelsPerUnit / max(-p.z, 1e-6), uPixelRange.x, uPixelRange.y);
}
)";

inline constexpr const char* kPointFragment = R"(#version 330 core
uniform vec3 uColour;
out vec4 fragColour;
void main() {
  vec2 d = gl_PointCoord - vec2(0.5);
  float r = dot(d, d);
  if (r > 0.25) discard;
  fragColour = vec4(r > 0.12 ? vec3(0.05) : uColour, 1.0);
}
)";

// Lines of one colour (the control cage).
inline constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uView;
uniform mat4 uProjection;
void main() { gl_Position = uProjection * uView * vec4(aPosition, 1.0); }
)";

inline constexpr const char* kLineFragment = R"(#version 330 core
uniform vec3 uColour;
out vec4 fragColour;
void main() { fragColour = vec4(uColour, 1.0); }
)";

}  // namespace tessera::view::shaders
