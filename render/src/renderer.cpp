#include "sutura/render/renderer.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "color_space.hpp"
#include "colormap.hpp"
#include "gl_api.hpp"
#include "legend.hpp"
#include "markers.hpp"
#include "offscreen_target.hpp"
#include "shaders.hpp"
#include "surface_geometry.hpp"
#include "vec3.hpp"

namespace sutura::render {
namespace {

constexpr int kMaxSize = 8192;
// Polylines and points are pulled towards the eye by this fraction of the scene's bounding
// radius (see the marker vertex shader): enough to win over the surface they lie on and over
// the chords of a polyline sampled on a curved surface, far too little to show through.
constexpr float kMarkerDepthBias = 0.01f;
// Surfaces are pushed back by glPolygonOffset(factor, units) so the wireframe drawn at the
// same depth (GL_LINES along the edges, no offset) stays visible.
constexpr float kSurfaceOffsetFactor = 1.0f;
constexpr float kSurfaceOffsetUnits = 1.0f;

void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
    throw GlError("render size " + std::to_string(width) + "x" + std::to_string(height) +
                  " outside [1, " + std::to_string(kMaxSize) + "]");
  }
}

const GlContext& made_current(GlContext& context) {
  context.make_current();
  return context;
}

// A GL buffer object that grows but never shrinks, so redrawing a scene of the same size
// reuses its storage (glBufferSubData) instead of reallocating.
struct StreamBuffer {
  GLuint id = 0;
  std::size_t capacity = 0;

  /// Binds the buffer to `target` and replaces its leading bytes with `data`.
  void upload(const GlApi& gl, GLenum target, const void* data, std::size_t bytes) {
    gl.BindBuffer(target, id);
    if (bytes > capacity) {
      gl.BufferData(target, static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_DRAW);
      capacity = bytes;
    } else if (bytes > 0) {
      gl.BufferSubData(target, 0, static_cast<GLsizeiptr>(bytes), data);
    }
  }
};

// GPU copy of one SurfaceItem: interleaved SurfaceVertex array, triangle indices and, with
// the wireframe on, edge indices.
struct SurfaceBuffers {
  GLuint vao = 0;
  StreamBuffer vertices;
  StreamBuffer indices;
  StreamBuffer edges;
};

void float_attribute(const GlApi& gl, GLuint location, int components, std::size_t stride,
                     std::size_t offset) {
  gl.EnableVertexAttribArray(location);
  gl.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                         reinterpret_cast<const void*>(offset));
}

// Pass state derived once per frame.
struct FrameSetup {
  std::array<float, 16> view;
  std::array<float, 16> projection;
  float marker_bias;
  bool multisampled;
  std::array<float, 4> clip;  ///< u_clip: (n, -n.p), or (0, 0, 0, -1) without a clip plane
};

// The scene's clip plane as the shaders' u_clip. Throws std::invalid_argument for a
// non-finite point or normal, or a zero normal.
std::array<float, 4> clip_uniform(const Scene& scene) {
  if (!scene.clip) return {0.0f, 0.0f, 0.0f, -1.0f};
  const Point3& p = scene.clip->point;
  const Point3& n = scene.clip->normal;
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(p[k]) || !std::isfinite(n[k]))
      throw std::invalid_argument("clip plane: the point and the normal must be finite");
  const float len = length(n);
  if (!(len > 0.0f) || !std::isfinite(len))
    throw std::invalid_argument("clip plane: the normal must not be zero");
  const Point3 u = {n[0] / len, n[1] / len, n[2] / len};
  return {u[0], u[1], u[2], -(u[0] * p[0] + u[1] * p[1] + u[2] * p[2])};
}

}  // namespace

struct Renderer::Impl {
  GlContext& context;
  GlApi gl;
  Programs programs;
  OffscreenTarget target;
  std::array<GLuint, 3> colormaps{};  // textures, indexed by ColorMapName
  std::vector<SurfaceBuffers> surfaces;
  GLuint marker_vao = 0;
  StreamBuffer marker_vertices;
  GLuint overlay_vao = 0;
  StreamBuffer overlay_vertices;
  GLint max_samples = 1;
  GLint max_renderbuffer_size = 0;
  // Scratch arrays kept between frames to avoid reallocating them.
  std::vector<SurfaceVertex> surface_scratch;
  std::vector<std::uint32_t> edge_scratch;
  std::vector<MarkerVertex> marker_scratch;

  explicit Impl(GlContext& c) : context(c), gl(made_current(c)), programs(gl), target(gl) {
    gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer_size);
    create_colormap_textures();
    gl.GenVertexArrays(1, &marker_vao);
    gl.GenBuffers(1, &marker_vertices.id);
    gl.BindVertexArray(marker_vao);
    marker_vertices.upload(gl, GL_ARRAY_BUFFER, nullptr, 0);
    constexpr std::size_t kMarkerStride = sizeof(MarkerVertex);
    float_attribute(gl, marker_attribute::kFrom, 3, kMarkerStride, offsetof(MarkerVertex, from));
    float_attribute(gl, marker_attribute::kTo, 3, kMarkerStride, offsetof(MarkerVertex, to));
    float_attribute(gl, marker_attribute::kCorner, 2, kMarkerStride,
                    offsetof(MarkerVertex, corner));
    float_attribute(gl, marker_attribute::kColor, 3, kMarkerStride, offsetof(MarkerVertex, color));
    float_attribute(gl, marker_attribute::kSize, 1, kMarkerStride, offsetof(MarkerVertex, size_px));
    float_attribute(gl, marker_attribute::kDisc, 1, kMarkerStride, offsetof(MarkerVertex, disc));
    gl.GenVertexArrays(1, &overlay_vao);
    gl.GenBuffers(1, &overlay_vertices.id);
    gl.BindVertexArray(overlay_vao);
    overlay_vertices.upload(gl, GL_ARRAY_BUFFER, nullptr, 0);
    float_attribute(gl, attribute::kPosition, 2, sizeof(OverlayVertex), offsetof(OverlayVertex, x));
    float_attribute(gl, attribute::kScalar, 1, sizeof(OverlayVertex),
                    offsetof(OverlayVertex, scalar));
    float_attribute(gl, attribute::kColor, 3, sizeof(OverlayVertex), offsetof(OverlayVertex, r));
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    gl.check("creating the renderer");
  }

  ~Impl() {
    // GL objects belong to the context; make sure it is the current one while deleting.
    context.make_current();
    for (SurfaceBuffers& s : surfaces) {
      gl.DeleteVertexArrays(1, &s.vao);
      gl.DeleteBuffers(1, &s.vertices.id);
      gl.DeleteBuffers(1, &s.indices.id);
      gl.DeleteBuffers(1, &s.edges.id);
    }
    gl.DeleteVertexArrays(1, &marker_vao);
    gl.DeleteBuffers(1, &marker_vertices.id);
    gl.DeleteVertexArrays(1, &overlay_vao);
    gl.DeleteBuffers(1, &overlay_vertices.id);
    gl.DeleteTextures(static_cast<GLsizei>(colormaps.size()), colormaps.data());
  }

  void create_colormap_textures() {
    gl.GenTextures(static_cast<GLsizei>(colormaps.size()), colormaps.data());
    for (std::size_t i = 0; i < colormaps.size(); ++i) {
      const ColormapTable table = colormap_table(static_cast<ColorMapName>(i));
      gl.BindTexture(GL_TEXTURE_2D, colormaps[i]);
      gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
      // sRGB internal format: the sampler converts entries to linear before filtering.
      gl.TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, kColormapSize, 1, 0, GL_RGBA,
                    GL_UNSIGNED_BYTE, table.data());
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    gl.BindTexture(GL_TEXTURE_2D, 0);
  }

  SurfaceBuffers& surface_buffers(std::size_t i) {
    while (surfaces.size() <= i) {
      SurfaceBuffers s;
      gl.GenVertexArrays(1, &s.vao);
      gl.GenBuffers(1, &s.vertices.id);
      gl.GenBuffers(1, &s.indices.id);
      gl.GenBuffers(1, &s.edges.id);
      gl.BindVertexArray(s.vao);
      s.vertices.upload(gl, GL_ARRAY_BUFFER, nullptr, 0);
      float_attribute(gl, attribute::kPosition, 3, sizeof(SurfaceVertex),
                      offsetof(SurfaceVertex, position));
      float_attribute(gl, attribute::kNormal, 3, sizeof(SurfaceVertex),
                      offsetof(SurfaceVertex, normal));
      float_attribute(gl, attribute::kScalar, 1, sizeof(SurfaceVertex),
                      offsetof(SurfaceVertex, scalar));
      surfaces.push_back(s);
    }
    return surfaces[i];
  }

  static void set_frame_uniforms(const GlApi& gl, const ShaderProgram& p, const FrameSetup& f) {
    gl.UniformMatrix4fv(p.uniform("u_view"), 1, GL_FALSE, f.view.data());
    gl.UniformMatrix4fv(p.uniform("u_projection"), 1, GL_FALSE, f.projection.data());
    gl.Uniform4f(p.uniform("u_clip"), f.clip[0], f.clip[1], f.clip[2], f.clip[3]);
  }

  void draw_surfaces(const Scene& scene, const FrameSetup& f) {
    const ColorMap map = scene.color_map.value_or(ColorMap{});
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, colormaps[static_cast<std::size_t>(map.name)]);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(kSurfaceOffsetFactor, kSurfaceOffsetUnits);
    for (std::size_t i = 0; i < scene.surfaces.size(); ++i) {
      const SurfaceItem& item = scene.surfaces[i];
      if (item.triangles.empty()) continue;
      build_surface_vertices(item, map, surface_scratch);
      SurfaceBuffers& buffers = surface_buffers(i);
      gl.BindVertexArray(buffers.vao);
      buffers.vertices.upload(gl, GL_ARRAY_BUFFER, surface_scratch.data(),
                              surface_scratch.size() * sizeof(SurfaceVertex));
      buffers.indices.upload(gl, GL_ELEMENT_ARRAY_BUFFER, item.triangles.data(),
                             item.triangles.size_bytes());
      const auto count = static_cast<GLsizei>(item.triangles.size());

      const ShaderProgram& surface = programs.surface;
      surface.use();
      set_frame_uniforms(gl, surface, f);
      gl.Uniform3f(surface.uniform("u_color"), item.color[0], item.color[1], item.color[2]);
      gl.Uniform1i(surface.uniform("u_use_scalars"), item.scalars.empty() ? 0 : 1);
      gl.Uniform1i(surface.uniform("u_colormap"), 0);
      gl.DepthFunc(GL_LESS);
      gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);

      if (item.wireframe) {
        const ShaderProgram& wire = programs.wire;
        wire.use();
        set_frame_uniforms(gl, wire, f);
        gl.Uniform3f(wire.uniform("u_color"), item.wire_color[0], item.wire_color[1],
                     item.wire_color[2]);
        gl.DepthFunc(GL_LEQUAL);
        build_edge_indices(item.triangles, edge_scratch);
        // Binds the edge list as the vertex array's element buffer; the triangle upload
        // above rebinds the triangles on the next draw.
        buffers.edges.upload(gl, GL_ELEMENT_ARRAY_BUFFER, edge_scratch.data(),
                             edge_scratch.size() * sizeof(std::uint32_t));
        gl.DrawElements(GL_LINES, static_cast<GLsizei>(edge_scratch.size()), GL_UNSIGNED_INT,
                        nullptr);
      }
    }
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.DepthFunc(GL_LESS);
  }

  void draw_markers(const Scene& scene, const FrameSetup& f, int width, int height) {
    build_marker_vertices(scene, marker_scratch);
    if (marker_scratch.empty()) return;
    gl.BindVertexArray(marker_vao);
    marker_vertices.upload(gl, GL_ARRAY_BUFFER, marker_scratch.data(),
                           marker_scratch.size() * sizeof(MarkerVertex));
    const ShaderProgram& p = programs.marker;
    p.use();
    set_frame_uniforms(gl, p, f);
    gl.Uniform1f(p.uniform("u_depth_bias"), f.marker_bias);
    gl.Uniform2f(p.uniform("u_viewport"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform1i(p.uniform("u_multisampled"), f.multisampled ? 1 : 0);
    // Markers are depth-tested against the surfaces but do not write depth: among themselves
    // they stack in drawing order (GL keeps primitive order), so a point on a polyline
    // vertex is never cut by the line's flat screen-space quad.
    gl.DepthMask(GL_FALSE);
    if (f.multisampled) {
      gl.Enable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      gl.Enable(GL_SAMPLE_ALPHA_TO_ONE);
    }
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(marker_scratch.size()));
    gl.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    gl.Disable(GL_SAMPLE_ALPHA_TO_ONE);
    gl.DepthMask(GL_TRUE);
  }

  void draw_legend(const Scene& scene, int width, int height) {
    const std::vector<OverlayVertex> triangles =
        legend_triangles(*scene.color_map, width, height, scene.background);
    if (triangles.empty()) return;
    gl.Disable(GL_DEPTH_TEST);
    gl.BindVertexArray(overlay_vao);
    overlay_vertices.upload(gl, GL_ARRAY_BUFFER, triangles.data(),
                            triangles.size() * sizeof(OverlayVertex));
    const ShaderProgram& p = programs.overlay;
    p.use();
    gl.Uniform2f(p.uniform("u_viewport"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform1i(p.uniform("u_colormap"), 0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, colormaps[static_cast<std::size_t>(scene.color_map->name)]);
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size()));
  }

  /// Clears the bound draw framebuffer and draws the whole scene into it. Leaves depth test,
  /// blending and face culling off, depth writes on, and program, vertex array, buffer and
  /// texture bindings at 0.
  void draw_scene(const Scene& scene, const Camera& camera, int width, int height,
                  bool multisampled, const RenderOptions& options, int x0 = 0, int y0 = 0) {
    // Everything that can reject the input comes before the first GL state change.
    for (const SurfaceItem& item : scene.surfaces) validate_surface(item);
    const std::array<float, 4> clip = clip_uniform(scene);
    const std::array<Point3, 2> bounds = scene_bounds(scene);
    const bool legend = options.draw_legend && scene.color_map && scene.color_map->show_legend;
    // The scene is drawn left of the legend's column, never under it.
    const int scene_width = width - (legend || options.legend_space ? legend_width(scene, width, height) : 0);
    const float aspect = static_cast<float>(scene_width) / static_cast<float>(height);
    const std::array<float, 2> depth = depth_range(camera, bounds);
    const float radius = 0.5f * length(bounds[1] - bounds[0]);
    const FrameSetup frame{view_matrix(camera),
                           projection_matrix(camera, aspect, depth[0], depth[1]),
                           kMarkerDepthBias * radius, multisampled, clip};

    gl.Viewport(x0, y0, width, height);
    gl.ClearColor(srgb_from_linear(scene.background[0]), srgb_from_linear(scene.background[1]),
                  srgb_from_linear(scene.background[2]), 1.0f);
    gl.ClearDepth(1.0);
    gl.DepthMask(GL_TRUE);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);  // both sides of every surface are drawn
    gl.Disable(GL_BLEND);

    gl.Viewport(x0, y0, scene_width, height);
    draw_surfaces(scene, frame);
    draw_markers(scene, frame, scene_width, height);
    if (legend) {
      gl.Viewport(x0, y0, width, height);
      draw_legend(scene, width, height);
    }

    gl.Disable(GL_DEPTH_TEST);
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.UseProgram(0);
    gl.check("drawing the scene");
  }

  Image render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options) {
    check_size(width, height);
    context.make_current();
    if (width > max_renderbuffer_size || height > max_renderbuffer_size) {
      throw GlError("render size " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds the GL limit of " + std::to_string(max_renderbuffer_size));
    }
    GLint previous_draw = 0;
    GLint previous_read = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_draw);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);

    const auto restore_bindings = [&] {
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
    };

    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    try {
      const int samples = render_samples(options.samples, width, height, max_samples);
      target.ensure(width, height, samples);
      gl.BindFramebuffer(GL_FRAMEBUFFER, target.draw_framebuffer());
      draw_scene(scene, camera, width, height, samples > 1, options);
      target.resolve();
      gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
      read_pixels(image);
    } catch (...) {
      restore_bindings();
      throw;
    }
    restore_bindings();
    return image;
  }

  // Reads image.width x image.height pixels of the read framebuffer, top row first.
  void read_pixels(Image& image) {
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    gl.check("reading the rendered image");
    // GL's first row is the bottom one; images are stored top row first.
    const std::size_t row = 4 * static_cast<std::size_t>(image.width);
    std::vector<std::uint8_t> swap(row);
    for (int y = 0; y < image.height / 2; ++y) {
      std::uint8_t* top = &image.rgba[row * static_cast<std::size_t>(y)];
      std::uint8_t* bottom = &image.rgba[row * static_cast<std::size_t>(image.height - 1 - y)];
      std::memcpy(swap.data(), top, row);
      std::memcpy(top, bottom, row);
      std::memcpy(bottom, swap.data(), row);
    }
  }

  Image read_bound(int width, int height) {
    check_size(width, height);
    Image image(width, height);
    read_pixels(image);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
  }

  void draw(const Scene& scene, const Camera& camera, int width, int height,
            const RenderOptions& options) {
    check_size(width, height);
    GLint sample_buffers = 0;
    gl.GetIntegerv(GL_SAMPLE_BUFFERS, &sample_buffers);
    // The scissor box limits the clear to this viewport (side-by-side views in one window).
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(options.viewport_x, options.viewport_y, width, height);
    try {
      draw_scene(scene, camera, width, height, sample_buffers > 0, options, options.viewport_x,
                 options.viewport_y);
    } catch (...) {
      gl.Disable(GL_SCISSOR_TEST);
      throw;
    }
    gl.Disable(GL_SCISSOR_TEST);
  }
};

int legend_width(const Scene& scene, int width, int height) {
  return scene.color_map ? legend_width(*scene.color_map, width, height) : 0;
}

// llvmpipe keeps every sample of a multisampled framebuffer in memory (colour and depth, 8
// bytes each) and clears them all: 4 samples of 8192 x 8192 pixels are 2.1 GB to touch and
// clear per render. The budget gives full anti-aliasing up to 4096 x 4096, where it is
// visible, and none at 8192 x 8192, where a pixel is too small for the edges to need it.
int render_samples(int requested, int width, int height, int max_samples) {
  constexpr std::int64_t kSampleBudget = 4LL * 4096 * 4096;
  const std::int64_t pixels = std::max<std::int64_t>(1, std::int64_t(width) * height);
  const int within_budget = int(std::min<std::int64_t>(kSampleBudget / pixels, 64));
  return std::clamp(std::min(requested, within_budget), 1, std::max(max_samples, 1));
}

Image Renderer::read_framebuffer(int width, int height) {
  return impl_->read_bound(width, height);
}

Renderer::Renderer(GlContext& context) : impl_(std::make_unique<Impl>(context)) {}
Renderer::~Renderer() = default;

Image Renderer::render(const Scene& scene, const Camera& camera, int width, int height,
                       const RenderOptions& options) {
  return impl_->render(scene, camera, width, height, options);
}

void Renderer::draw(const Scene& scene, const Camera& camera, int width, int height,
                    const RenderOptions& options) {
  impl_->draw(scene, camera, width, height, options);
}

}  // namespace sutura::render
