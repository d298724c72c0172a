#pragma once
// GLSL 3.30 programs of the renderer. Each is compiled and linked once per Renderer (a few
// ms each); llvmpipe JIT-compiles them to machine code at their first draw (tens of ms, kept
// in Mesa's on-disk shader cache). All fragment shaders take linear colours and write
// sRGB-encoded ones.
#include "gl_api.hpp"

namespace sutura::render {

/// A linked program; owns the GL object. The context must be current when it is destroyed.
class ShaderProgram {
 public:
  /// Throws GlError with the compiler's or linker's log.
  ShaderProgram(const GlApi& gl, const char* name, const char* vertex, const char* fragment);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const { gl_.UseProgram(id_); }
  /// Location of a uniform, -1 if the linker dropped it (GL ignores writes to -1).
  [[nodiscard]] GLint uniform(const char* name) const { return gl_.GetUniformLocation(id_, name); }

 private:
  const GlApi& gl_;
  GLuint id_ = 0;
};

/// Vertex attribute locations of the surface, wire and overlay programs.
namespace attribute {
inline constexpr GLuint kPosition = 0;  ///< vec3 world position (vec2 pixels for the overlay)
inline constexpr GLuint kNormal = 1;    ///< vec3 world normal (surfaces)
inline constexpr GLuint kScalar = 2;    ///< float colour-map coordinate in [0, 1], < 0: none
inline constexpr GLuint kColor = 3;     ///< vec3 linear colour (overlay)
}  // namespace attribute

/// Vertex attribute locations of the marker program, one per MarkerVertex field.
namespace marker_attribute {
inline constexpr GLuint kFrom = 0;
inline constexpr GLuint kTo = 1;
inline constexpr GLuint kCorner = 2;
inline constexpr GLuint kColor = 3;
inline constexpr GLuint kSize = 4;
inline constexpr GLuint kDisc = 5;
}  // namespace marker_attribute

/// The renderer's programs (vertex and fragment stages only: see markers.hpp for why).
/// - surface: two-sided lit triangles, uniform colour or colour map.
/// - wire: plain transformed positions in one colour (wireframe edges as GL_LINES).
/// - marker: polyline segments and round anti-aliased discs expanded in screen space.
/// - overlay: 2D pixel-space triangles (legend), colour or colour map per vertex.
struct Programs {
  explicit Programs(const GlApi& gl);
  ShaderProgram surface;
  ShaderProgram wire;
  ShaderProgram marker;
  ShaderProgram overlay;
};

}  // namespace sutura::render
