#include "world/renderer.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "world/mujoco_errors.hpp"
#include "world/scene.hpp"
#include "world/state_rules.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

std::mutex egl_mutex;  // context creation and destruction are not thread-safe in Mesa
// The offscreen buffer's largest side (pixels): tiles fill rows of it.
constexpr int kMaxBufferSide = 8192;

struct Display {
  EGLDisplay display = EGL_NO_DISPLAY;
  const char* platform = "";
};

// $CHORE_EGL: "auto" (default: a GPU device if present, else surfaceless),
// "device" or "surfaceless".
Display open_display() {
  // llvmpipe would start its own rasteriser threads in every context, competing
  // with chore's workers for the cores; each worker renders on its own thread.
  setenv("LP_NUM_THREADS", "0", 0);
  const char* choice_env = std::getenv("CHORE_EGL");
  const std::string choice = choice_env && *choice_env ? choice_env : "auto";
  if (choice != "auto" && choice != "device" && choice != "surfaceless") {
    throw Error("CHORE_EGL='" + choice + "': expected auto, device or surfaceless");
  }
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) throw Error("EGL: eglGetPlatformDisplayEXT is not available");
  Display d;
  if (choice != "surfaceless") {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices && query_device_string && query_devices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        const char* ext = query_device_string(devices[i], EGL_EXTENSIONS);
        if (ext && std::strstr(ext, "EGL_MESA_device_software")) continue;  // llvmpipe
        EGLDisplay candidate = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        EGLint major, minor;
        if (candidate != EGL_NO_DISPLAY && eglInitialize(candidate, &major, &minor)) {
          d = {candidate, "device"};
          break;
        }
      }
    }
    if (d.display == EGL_NO_DISPLAY && choice == "device") {
      throw Error("EGL: cannot open a display: CHORE_EGL=device but no GPU EGL device was found");
    }
  }
  if (d.display == EGL_NO_DISPLAY) {
    EGLDisplay candidate = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major, minor;
    if (candidate == EGL_NO_DISPLAY || !eglInitialize(candidate, &major, &minor)) {
      throw Error("EGL: cannot open a display: surfaceless Mesa platform failed (error 0x" +
                  std::to_string(eglGetError()) + "); is libegl-mesa0 installed?");
    }
    d = {candidate, "surfaceless"};
  }
  return d;
}

const Display& display() {
  // Not a function-local static initialised once and for all: a failure
  // (bad $CHORE_EGL) must be reported again to the next caller, not cached.
  static std::mutex mutex;
  static Display d;
  std::lock_guard<std::mutex> lock(mutex);
  if (d.display == EGL_NO_DISPLAY) d = open_display();
  return d;
}

}  // namespace

struct Renderer::State {
  EGLContext context = EGL_NO_CONTEXT;
  int width = 0, height = 0, tiles = 1;
  int columns = 1;  // tiles per row of the offscreen buffer; tile t at column t % columns, row t / columns
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjrContext render_context;
  std::vector<unsigned char> rgb;
  std::vector<float> depth;
  // Whose textures the context holds (see use_textures); none known at first.
  std::pair<const World*, int> textures{nullptr, 0};
  bool textures_uploaded = false;

  void make_current() const {
    if (eglGetCurrentContext() != context &&
        !eglMakeCurrent(display().display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      throw Error("EGL: cannot make the render context current on this thread");
    }
  }
};

Renderer::Renderer(const mjModel* model, int width, int height, int max_tiles) : state_(std::make_unique<State>()) {
  install_mujoco_handlers();
  if (width <= 0 || height <= 0 || width > 4096 || height > 4096) {
    throw Error("renderer: image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1..4096");
  }
  if (max_tiles <= 0) throw Error("renderer: max_tiles must be positive");
  State& s = *state_;
  s.width = width;
  s.height = height;
  s.tiles = max_tiles;
  s.columns = std::min(max_tiles, kMaxBufferSide / width);
  const int rows = (max_tiles + s.columns - 1) / s.columns;
  if (rows * height > kMaxBufferSide) {
    throw Error("renderer: " + std::to_string(max_tiles) + " tiles of " + std::to_string(width) + "x" +
                std::to_string(height) + " exceed the " + std::to_string(kMaxBufferSide) + "x" +
                std::to_string(kMaxBufferSide) + " offscreen buffer");
  }
  {
    std::lock_guard<std::mutex> lock(egl_mutex);
    const EGLDisplay dpy = display().display;
    const EGLint attributes[] = {EGL_SURFACE_TYPE,
                                 EGL_PBUFFER_BIT,
                                 EGL_RED_SIZE,
                                 8,
                                 EGL_GREEN_SIZE,
                                 8,
                                 EGL_BLUE_SIZE,
                                 8,
                                 EGL_ALPHA_SIZE,
                                 8,
                                 EGL_DEPTH_SIZE,
                                 24,
                                 EGL_RENDERABLE_TYPE,
                                 EGL_OPENGL_BIT,
                                 EGL_NONE};
    EGLConfig config;
    EGLint configs = 0;
    if (!eglChooseConfig(dpy, attributes, &config, 1, &configs) || configs < 1) {
      throw Error("EGL: no RGBA8 + depth24 OpenGL config on this display");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL: cannot bind the OpenGL API");
    s.context = eglCreateContext(dpy, config, EGL_NO_CONTEXT, nullptr);
    if (s.context == EGL_NO_CONTEXT) throw Error("EGL: cannot create an OpenGL context");
  }
  s.make_current();
  mjv_defaultScene(&s.scene);
  // Room for the model's geoms and for decor (dirt particles).
  mjv_makeScene(model, &s.scene, model->ngeom + 1000);
  mjv_defaultOption(&s.option);
  // Drawn: groups 0 and 2 (the merged static scene) and, per view, the
  // ceilings; collision geoms stay hidden.
  for (int g = 0; g < mjNGROUP; ++g) {
    s.option.geomgroup[g] = g == kStaticGroup || g == kMergedGroup;
    s.option.sitegroup[g] = 0;
  }
  mjv_defaultCamera(&s.camera);
  s.camera.type = mjCAMERA_FIXED;
  s.scene.flags[mjRND_SHADOW] = 0;
  s.scene.flags[mjRND_REFLECTION] = 0;
  s.scene.flags[mjRND_SKYBOX] = 0;
  s.scene.flags[mjRND_FOG] = 0;
  // The offscreen buffer size is read from the model; a shallow copy of the
  // struct with our size leaves the shared model untouched.
  mjModel sized = *model;
  sized.vis.global.offwidth = s.columns * width;
  sized.vis.global.offheight = rows * height;
  sized.vis.quality.offsamples = 0;
  mjr_defaultContext(&s.render_context);
  mjr_makeContext(&sized, &s.render_context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &s.render_context);
  if (s.render_context.currentBuffer != mjFB_OFFSCREEN) {
    throw Error("renderer: the offscreen framebuffer is not supported by this OpenGL context");
  }
  s.rgb.resize(3 * size_t(s.columns * width) * rows * height);
  s.depth.resize(size_t(s.columns * width) * rows * height);
}

Renderer::~Renderer() {
  if (!state_ || state_->context == EGL_NO_CONTEXT) return;
  State& s = *state_;
  std::lock_guard<std::mutex> lock(egl_mutex);
  if (eglMakeCurrent(display().display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context)) {
    mjr_freeContext(&s.render_context);
    mjv_freeScene(&s.scene);
    eglMakeCurrent(display().display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display().display, s.context);
}

void Renderer::release_thread() {
  if (state_ && eglGetCurrentContext() == state_->context) {
    eglMakeCurrent(display().display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

int Renderer::width() const {
  return state_->width;
}
int Renderer::height() const {
  return state_->height;
}
int Renderer::max_tiles() const {
  return state_->tiles;
}
int Renderer::tile_capacity(int width, int height) {
  return width <= 0 || height <= 0 ? 0 : (kMaxBufferSide / width) * (kMaxBufferSide / height);
}
const char* Renderer::platform() {
  return display().platform;
}

namespace {

// Drops geoms whose bounding sphere lies outside the camera's view frustum:
// MuJoCo 2.2.2 draws every geom, and each draw costs ~30 us on llvmpipe.
void cull_to_frustum(mjvScene& scene, double aspect) {
  const mjvGLCamera& cam = scene.camera[0];
  const float* f = cam.forward;
  const float* u = cam.up;
  const float right[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
  const double half_height = (cam.frustum_top - cam.frustum_bottom) / 2;
  const double tan_v = half_height / cam.frustum_near;
  const double tan_h = tan_v * aspect;
  const double slack_v = std::sqrt(1 + tan_v * tan_v), slack_h = std::sqrt(1 + tan_h * tan_h);
  int kept = 0;
  for (int i = 0; i < scene.ngeom; ++i) {
    const mjvGeom& g = scene.geoms[i];
    const double r = g.modelrbound;
    bool visible = true;
    if (r > 0) {  // 0: not a model geom, or unbounded (planes): always drawn
      double p[3];
      for (int k = 0; k < 3; ++k) p[k] = g.pos[k] - cam.pos[k];
      const double z = p[0] * f[0] + p[1] * f[1] + p[2] * f[2];
      const double y = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
      const double x = p[0] * right[0] + p[1] * right[1] + p[2] * right[2];
      visible = z > cam.frustum_near - r && z < cam.frustum_far + r && std::abs(y) <= tan_v * z + r * slack_v &&
                std::abs(x) <= tan_h * z + r * slack_h;
    }
    if (visible) scene.geoms[kept++] = g;
  }
  scene.ngeom = kept;
}

}  // namespace

// One camera drawn once: in colour (RGB and depth) or in segmentation colours.
struct Renderer::Draw {
  const CameraView* view;
  bool segment;
  std::vector<int> segid_geom;  // segmentation pass: scene geom segid -> model geom id
};

void Renderer::render(std::span<const CameraView> views) {
  State& s = *state_;
  s.make_current();
  std::vector<Draw> draws;
  for (const CameraView& v : views) {
    if (v.camera < 0 || v.camera >= v.model->ncam) {
      throw Error("renderer: camera id " + std::to_string(v.camera) + " out of range");
    }
    if (v.tile < 0 || v.tile >= s.tiles) {
      throw Error("renderer: tile " + std::to_string(v.tile) + " outside 0.." + std::to_string(s.tiles - 1));
    }
    if (v.rgb || (v.depth && !v.segment)) draws.push_back({&v, false, {}});
    if (v.segment) draws.push_back({&v, true, {}});
  }
  std::vector<Draw*> todo;
  for (Draw& d : draws) todo.push_back(&d);
  // Passes in which each tile is drawn at most once.
  while (!todo.empty()) {
    std::vector<Draw*> pass, later;
    std::vector<char> used(s.tiles, 0);
    for (Draw* d : todo) {
      (used[d->view->tile] ? later : pass).push_back(d);
      used[d->view->tile] = 1;
    }
    render_pass(pass);
    todo.swap(later);
  }
}

void Renderer::use_textures(const CameraView& v) {
  State& s = *state_;
  // Worlds with the scene's own textures share them; a randomised world has its own.
  const std::pair<const World*, int> key = v.world && v.world->texture_version()
                                               ? std::pair{v.world, v.world->texture_version()}
                                               : std::pair<const World*, int>{nullptr, 0};
  if (s.textures_uploaded && key == s.textures) return;
  for (int t = 0; t < v.model->ntex; ++t) mjr_uploadTexture(v.model, &s.render_context, t);
  s.textures = key;
  s.textures_uploaded = true;
}

void Renderer::render_pass(const std::vector<Draw*>& pass) {
  State& s = *state_;
  int first = s.tiles, last = -1;
  bool want_rgb = false, want_depth = false;
  // The depth of a view comes from its colour draw when it has one.
  auto reads_depth = [](const Draw& d) { return d.view->depth && (!d.segment || !d.view->rgb); };
  for (Draw* d : pass) {
    const CameraView* v = d->view;
    if (!d->segment) use_textures(*v);
    s.scene.flags[mjRND_SEGMENT] = s.scene.flags[mjRND_IDCOLOR] = d->segment;
    s.camera.fixedcamid = v->camera;
    s.option.geomgroup[kCeilingGroup] = v->ceiling;
    mjv_updateScene(v->model, v->data, &s.option, nullptr, &s.camera, mjCAT_ALL, &s.scene);
    if (v->world && !d->segment) draw_states(*v->world, &s.scene);
    cull_to_frustum(s.scene, double(s.width) / s.height);
    if (d->segment) {
      // MuJoCo colours a geom with its segid + 1 (r + 256 g + 65536 b).
      for (int i = 0; i < s.scene.ngeom; ++i) {
        const mjvGeom& g = s.scene.geoms[i];
        if (g.segid < 0) continue;
        if (g.segid >= static_cast<int>(d->segid_geom.size())) d->segid_geom.resize(g.segid + 1, -1);
        d->segid_geom[g.segid] = g.objtype == mjOBJ_GEOM ? g.objid : -1;
      }
    }
    const mjrRect viewport = {v->tile % s.columns * s.width, v->tile / s.columns * s.height, s.width, s.height};
    mjr_render(viewport, &s.scene, &s.render_context);
    first = std::min(first, v->tile);
    last = std::max(last, v->tile);
    want_rgb |= d->segment || v->rgb;
    want_depth |= reads_depth(*d);
  }
  // One readback for the pass: of the span of tiles drawn within a row, or
  // of the whole rows they span.
  const int first_row = first / s.columns, last_row = last / s.columns;
  const int first_column = first_row == last_row ? first % s.columns : 0;
  const int read_width = (first_row == last_row ? last - first + 1 : s.columns) * s.width;
  const int read_height = (last_row - first_row + 1) * s.height;
  const mjrRect read = {first_column * s.width, first_row * s.height, read_width, read_height};
  mjr_readPixels(want_rgb ? s.rgb.data() : nullptr, want_depth ? s.depth.data() : nullptr, read, &s.render_context);
  for (const Draw* d : pass) {
    const CameraView* v = d->view;
    const int x0 = (v->tile % s.columns - first_column) * s.width;
    const int y0 = (v->tile / s.columns - first_row) * s.height;
    const double extent = v->model->stat.extent;
    const double near = v->model->vis.map.znear * extent, far = v->model->vis.map.zfar * extent;
    for (int row = 0; row < s.height; ++row) {
      // OpenGL rows run bottom-up.
      const size_t src = size_t(y0 + s.height - 1 - row) * read_width + x0;
      if (d->segment) {
        std::int32_t* out = v->segment + size_t(row) * s.width;
        const unsigned char* in = s.rgb.data() + 3 * src;
        const int known = static_cast<int>(d->segid_geom.size());
        for (int col = 0; col < s.width; ++col) {
          const int id = in[3 * col] | in[3 * col + 1] << 8 | in[3 * col + 2] << 16;
          out[col] = id > 0 && id <= known ? d->segid_geom[id - 1] : -1;
        }
      } else if (v->rgb) {
        std::memcpy(v->rgb + size_t(row) * s.width * 3, s.rgb.data() + 3 * src, 3 * s.width);
      }
      if (reads_depth(*d)) {
        float* out = v->depth + size_t(row) * s.width;
        const float* in = s.depth.data() + src;
        for (int col = 0; col < s.width; ++col) {
          // Depth buffer value to metric distance along the optical axis.
          out[col] = float(near / (1.0 - in[col] * (1.0 - near / far)));
        }
      }
    }
  }
}

}  // namespace chore
