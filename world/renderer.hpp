// Headless OpenGL rendering through EGL: a GPU's EGL device when there is one,
// else surfaceless Mesa (llvmpipe). One Renderer per thread: it owns an EGL
// context current on the thread that made it, and MuJoCo's render context.
//
// Several cameras are drawn per pass as tiles of one offscreen buffer (rows of
// tiles, up to 8192 x 8192 pixels) and read back once: on llvmpipe
// rasterisation happens at readback, so the per-frame overhead is paid once
// per pass rather than once per camera; on a GPU each readback is a
// synchronisation.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

struct mjModel_;
struct mjData_;

namespace chore {

struct CameraView {
  const mjModel_* model;
  mjData_* data;      // mjv_updateScene needs it non-const; it is not changed
  int camera;         // camera id in `model`
  std::uint8_t* rgb;  // height x width x 3, top row first; nullptr to skip
  // height x width metres along the optical axis; nullptr to skip. From the
  // colour pass when there is one, else from the segmentation pass.
  float* depth;
  // Where in the offscreen buffer it is drawn (0 .. max_tiles-1). llvmpipe's
  // rasteriser rounds differently at different offsets (a few pixels differ by
  // one level), so an environment that must render bit-identically keeps its tile.
  int tile = 0;
  bool ceiling = true;  // false for views from above the scene
  // When set, extended-state visuals of this world are drawn (soaked, cooked,
  // burnt and frozen colours, dirt particles; ObjectStates::draw),
  // and its randomised textures (World::texture_version) are used.
  const class World* world = nullptr;
  // height x width model geom id seen at each pixel (-1: none), from a second
  // pass with MuJoCo's segmentation rendering (flat colours, no decor); nullptr to skip.
  std::int32_t* segment = nullptr;
};

class Renderer {
 public:
  // `model` fixes the meshes and textures; every view must share them (copies
  // of one scene's model). Throws chore::Error when no EGL display can be opened.
  Renderer(const mjModel_* model, int width, int height, int max_tiles = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void render(std::span<const CameraView> views);
  // An EGL context is current on one thread at a time: after this, called on
  // the thread that rendered last, the next frame may be drawn on another.
  void release_thread();

  int width() const;
  int height() const;
  int max_tiles() const;
  // How many tiles of width x height the offscreen buffer holds at most.
  static int tile_capacity(int width, int height);
  // "surfaceless" or "device": which EGL platform this process uses.
  static const char* platform();

 private:
  struct Draw;
  void render_pass(const std::vector<Draw*>& pass);
  void use_textures(const CameraView& view);
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace chore
