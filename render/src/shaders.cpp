#include "shaders.hpp"

#include <string>

#include "colormap.hpp"

namespace sutura::render {
namespace {

constexpr const char* kVersion = "#version 330 core\n";

// Prepended to every fragment shader.
static_assert(kColormapSize == 256, "colormap() below assumes 256 texels");
constexpr const char* kFragmentCommon = R"(
out vec4 o_color;
uniform sampler2D u_colormap;  // 256x1 sRGB texture: sampling returns linear colour

// Exact sRGB transfer function, as color_space.hpp.
vec3 srgb_from_linear(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

// t in [0, 1] onto texel centres, so t = 0 and t = 1 give exactly the first and last entry.
vec3 colormap(float t) {
  return texture(u_colormap, vec2((clamp(t, 0.0, 1.0) * 255.0 + 0.5) / 256.0, 0.5)).rgb;
}

// Vertices without a finite scalar are drawn in this linear grey.
const vec3 kNoValue = vec3(0.35);

// The scene's clip plane (n, -n.p): world points with dot(u_clip, (x, 1)) > 0 are cut away.
// Without one the renderer sets (0, 0, 0, -1), which keeps everything.
uniform vec4 u_clip;
bool cut_away(vec3 world) { return dot(u_clip, vec4(world, 1.0)) > 0.0; }
)";

constexpr const char* kSurfaceVertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_scalar;
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_position;  // view space
out vec3 v_normal;    // view space, not normalised
out float v_scalar;
out vec3 v_world;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_position = p.xyz;
  v_world = a_position;
  v_normal = mat3(u_view) * a_normal;  // the view matrix is a rigid motion
  v_scalar = a_scalar;
  gl_Position = u_projection * p;
}
)";

// Blinn-Phong with a head light placed above-left of the eye (view space), computed in
// linear colour. The normal is flipped on back faces, so both sides of an open surface are
// lit alike.
constexpr const char* kSurfaceFragment = R"(
in vec3 v_position;
in vec3 v_normal;
in float v_scalar;
in vec3 v_world;
uniform vec3 u_color;
uniform bool u_use_scalars;
const vec3 kLightDir = normalize(vec3(-0.35, 0.45, 1.0));
const float kAmbient = 0.22;
const float kDiffuse = 0.78;
const float kSpecular = 0.15;
const float kShininess = 40.0;
void main() {
  if (cut_away(v_world)) discard;
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 to_eye = normalize(-v_position);
  vec3 base = u_color;
  if (u_use_scalars) base = v_scalar < 0.0 ? kNoValue : colormap(v_scalar);
  float diffuse = max(dot(n, kLightDir), 0.0);
  float specular = pow(max(dot(n, normalize(kLightDir + to_eye)), 0.0), kShininess);
  vec3 c = base * (kAmbient + kDiffuse * diffuse) + vec3(kSpecular * specular);
  o_color = vec4(srgb_from_linear(c), 1.0);
}
)";

constexpr const char* kWireVertex = R"(
layout(location = 0) in vec3 a_position;
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_world;
void main() {
  v_world = a_position;
  gl_Position = u_projection * (u_view * vec4(a_position, 1.0));
}
)";

constexpr const char* kWireFragment = R"(
in vec3 v_world;
uniform vec3 u_color;
void main() {
  if (cut_away(v_world)) discard;
  o_color = vec4(srgb_from_linear(u_color), 1.0);
}
)";

// Polyline segments and round discs (markers.hpp), expanded to screen-space quads here.
// A view-space depth bias slides each point along its eye ray towards the eye by
// u_depth_bias world units, so markers lying on a surface win the depth test without moving
// on screen (glPolygonOffset does not apply to them). Segments crossing the near plane are
// clipped first (the screen-space offset needs w > 0); primitives entirely behind it
// collapse to a point and produce no fragments.
constexpr const char* kMarkerVertex = R"(
layout(location = 0) in vec3 a_from;
layout(location = 1) in vec3 a_to;
layout(location = 2) in vec2 a_corner;
layout(location = 3) in vec3 a_color;
layout(location = 4) in float a_size_px;
layout(location = 5) in float a_disc;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_depth_bias;
uniform vec2 u_viewport;  // pixels
out vec3 v_color;
out vec2 v_offset_px;        // disc: from the centre
flat out float v_radius_px;  // disc radius; < 0 for segments
out vec3 v_world;            // the segment's end (interpolated along it) or the disc's centre

vec4 biased_clip(vec3 world) {
  vec4 p = u_view * vec4(world, 1.0);
  float d = length(p.xyz);
  if (d > 0.0) p.xyz *= max(d - u_depth_bias, 0.5 * d) / d;
  return u_projection * p;
}

void main() {
  vec2 half_viewport = 0.5 * u_viewport;
  v_color = a_color;
  vec4 c0 = biased_clip(a_from);
  v_world = a_from;
  if (a_disc > 0.5) {
    // One pixel beyond the rim, so the fragment shader can fade the edge.
    v_offset_px = a_corner * (0.5 * a_size_px + 1.0);
    v_radius_px = 0.5 * a_size_px;
    vec2 offset = v_offset_px / half_viewport * c0.w;
    gl_Position = c0.z < -c0.w ? vec4(0.0) : vec4(c0.xy + offset, c0.zw);
    return;
  }
  v_offset_px = vec2(0.0);
  v_radius_px = -1.0;
  vec4 c1 = biased_clip(a_to);
  float d0 = c0.z + c0.w;  // >= 0 in front of the near plane
  float d1 = c1.z + c1.w;
  if (d0 < 0.0 && d1 < 0.0) {
    gl_Position = vec4(0.0);
    return;
  }
  // The world points move with the clip-space ends, so the clip plane's test stays exact.
  vec3 w0 = a_from, w1 = a_to;
  if (d0 < 0.0) {
    c0 = mix(c0, c1, d0 / (d0 - d1));
    w0 = mix(a_from, a_to, d0 / (d0 - d1));
  }
  if (d1 < 0.0) {
    c1 = mix(c1, c0, d1 / (d1 - d0));
    w1 = mix(a_to, a_from, d1 / (d1 - d0));
  }
  v_world = a_corner.x < 0.5 ? w0 : w1;
  vec2 along = c1.xy / c1.w * half_viewport - c0.xy / c0.w * half_viewport;
  float len = length(along);
  vec2 normal = len > 1e-4 ? vec2(-along.y, along.x) / len : vec2(0.0);
  vec4 c = a_corner.x < 0.5 ? c0 : c1;
  gl_Position = vec4(c.xy + normal * (0.5 * a_size_px * a_corner.y) / half_viewport * c.w, c.zw);
}
)";

// Disc coverage of the pixel, approximated by the distance to the rim. Multisampled targets
// turn it into a sample mask (alpha to coverage, alpha then forced to one), which is
// anti-aliased, order independent and deterministic; single-sampled ones threshold it.
// Segments have full coverage; their edges are anti-aliased by multisampling itself.
constexpr const char* kMarkerFragment = R"(
in vec3 v_color;
in vec2 v_offset_px;
flat in float v_radius_px;
in vec3 v_world;
uniform bool u_multisampled;
void main() {
  if (cut_away(v_world)) discard;
  float coverage = 1.0;
  if (v_radius_px >= 0.0) coverage = clamp(v_radius_px - length(v_offset_px) + 0.5, 0.0, 1.0);
  if (coverage <= (u_multisampled ? 0.0 : 0.5)) discard;
  o_color = vec4(srgb_from_linear(v_color), u_multisampled ? coverage : 1.0);
}
)";

constexpr const char* kOverlayVertex = R"(
layout(location = 0) in vec2 a_position;  // pixels, origin top-left, y down
layout(location = 2) in float a_scalar;
layout(location = 3) in vec3 a_color;
uniform vec2 u_viewport;
out vec3 v_color;
out float v_scalar;
void main() {
  gl_Position = vec4(2.0 * a_position.x / u_viewport.x - 1.0,
                     1.0 - 2.0 * a_position.y / u_viewport.y, 0.0, 1.0);
  v_color = a_color;
  v_scalar = a_scalar;
}
)";

constexpr const char* kOverlayFragment = R"(
in vec3 v_color;
in float v_scalar;
void main() {
  vec3 c = v_scalar < 0.0 ? v_color : colormap(v_scalar);
  o_color = vec4(srgb_from_linear(c), 1.0);
}
)";

GLuint compile(const GlApi& gl, const char* program, GLenum stage, const char* body) {
  const bool fragment = stage == GL_FRAGMENT_SHADER;
  const char* parts[] = {kVersion, fragment ? kFragmentCommon : "", body};
  const GLuint shader = gl.CreateShader(stage);
  gl.ShaderSource(shader, 3, parts, nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    const char* kind = fragment ? "fragment" : "vertex";
    throw GlError(std::string("compiling the ") + program + " " + kind + " shader failed: " + log);
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const GlApi& gl, const char* name, const char* vertex,
                             const char* fragment)
    : gl_(gl) {
  const GLuint vs = compile(gl, name, GL_VERTEX_SHADER, vertex);
  GLuint fs = 0;
  try {
    fs = compile(gl, name, GL_FRAGMENT_SHADER, fragment);
  } catch (...) {
    gl.DeleteShader(vs);
    throw;
  }
  id_ = gl.CreateProgram();
  gl.AttachShader(id_, vs);
  gl.AttachShader(id_, fs);
  gl.LinkProgram(id_);
  gl.DeleteShader(vs);  // flagged for deletion, freed with the program
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetProgramInfoLog(id_, sizeof log, nullptr, log);
    gl.DeleteProgram(id_);
    throw GlError(std::string("linking the ") + name + " shader program failed: " + log);
  }
}

ShaderProgram::~ShaderProgram() { gl_.DeleteProgram(id_); }

Programs::Programs(const GlApi& gl)
    : surface(gl, "surface", kSurfaceVertex, kSurfaceFragment),
      wire(gl, "wire", kWireVertex, kWireFragment),
      marker(gl, "marker", kMarkerVertex, kMarkerFragment),
      overlay(gl, "overlay", kOverlayVertex, kOverlayFragment) {}

}  // namespace sutura::render
