#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "test_util.hpp"
#include "world/renderer.hpp"

namespace chore {
namespace {

void save_png(const Array& rgb, int index, int h, int w, const std::string& name) {
  cv::Mat img(h, w, CV_8UC3, const_cast<void*>(rgb.item(index)));
  cv::Mat bgr;
  cv::cvtColor(img, bgr, cv::COLOR_RGB2BGR);
  cv::imwrite((test::output_dir() / name).string(), bgr);
}

// Projects a world point into the egocentric camera: (column, row) in pixels.
std::array<double, 2> project(const mjModel* m, const mjData* d, int cam, const double p[3], int width, int height) {
  double rel[3], local[3];
  mju_sub3(rel, p, d->cam_xpos + 3 * cam);
  mju_mulMatTVec3(local, d->cam_xmat + 9 * cam, rel);  // camera frame: x right, y up, -z forward
  const double f = 0.5 * height / std::tan(m->cam_fovy[cam] * M_PI / 360.0);
  return {width / 2.0 + f * local[0] / -local[2], height / 2.0 - f * local[1] / -local[2]};
}

TEST(Render, DepthMatchesRayCastsWithinOneCentimetre) {
  Env env(test::box_room_config());
  auto r = env.reset(0);
  const mjModel* m = env.world().model();
  const mjData* d = env.world().data();
  const int cam = env.world().scene().camera();
  const float* depth = r.obs["depth"].data<float>();
  const int w = 128, h = 128;
  // Pixel centres' rays through the camera, compared with mj_ray's hit distance
  // projected on the optical axis (depth is distance along the axis).
  const double f = 0.5 * h / std::tan(m->cam_fovy[cam] * M_PI / 360.0);
  int checked = 0;
  for (int row : {16, 64, 100}) {
    for (int col : {20, 64, 110}) {
      const double local[3] = {(col + 0.5 - w / 2.0) / f, -(row + 0.5 - h / 2.0) / f, -1.0};
      double dir[3];
      mju_mulMatVec3(dir, d->cam_xmat + 9 * cam, local);
      const double norm = mju_norm3(dir);
      mju_scl3(dir, dir, 1.0 / norm);
      int geom = -1;
      const double hit = mj_ray(m, d, d->cam_xpos + 3 * cam, dir, nullptr, 1, m->cam_bodyid[cam], &geom, nullptr);
      ASSERT_GT(hit, 0) << row << "," << col;
      EXPECT_NEAR(depth[row * w + col], hit / norm, 0.01) << "pixel " << row << "," << col;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
  // The panel straight ahead: its face is at x = 2.45.
  const double centre_expected = 2.45 - d->cam_xpos[3 * cam];
  EXPECT_NEAR(depth[64 * w + 64], centre_expected, 0.01);
}

TEST(Render, ColouredObjectsAppearWhereTheyStand) {
  Env env(test::box_room_config());
  auto r = env.reset(0);
  const Array& rgb = r.obs["rgb"];
  save_png(rgb, 0, 128, 128, "box_room_head_camera.png");
  const std::uint8_t* px = rgb.data<std::uint8_t>();
  auto at = [&](double col, double row) {
    const std::uint8_t* p = px + 3 * (int(row) * 128 + int(col));
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  // Red panel straight ahead fills the centre.
  auto centre = at(64, 64);
  EXPECT_GT(centre[0], 2 * centre[1]);
  EXPECT_GT(centre[0], 2 * centre[2]);
  // The blue pillar at (2.0, 0.9) stands to the left: its projected centre is blue.
  const mjModel* m = env.world().model();
  const double pillar[3] = {2.0, 0.9, 1.1};
  auto uv = project(m, env.world().data(), env.world().scene().camera(), pillar, 128, 128);
  ASSERT_GT(uv[0], 0);
  ASSERT_LT(uv[0], 64);
  auto blue = at(uv[0], uv[1]);
  EXPECT_GT(blue[2], 2 * blue[0]) << uv[0] << "," << uv[1];
  EXPECT_GT(blue[2], 2 * blue[1]);
  // And the right edge of the image shows neither.
  auto right = at(124, 64);
  EXPECT_LT(std::abs(right[0] - right[2]), 40);
}

double mean_brightness(Env& env) {
  const Array& rgb = env.reset(0).obs["rgb"];
  double sum = 0;
  for (size_t i = 0; i < rgb.bytes.size(); ++i) sum += rgb.bytes[i];
  return sum / rgb.bytes.size();
}

TEST(Render, LampsOnlyLightingIsDarkerThanFull) {
  EnvConfig c = test::box_room_config();
  Env full(c);
  c.lighting = Lighting::lamps_only;
  Env lamps(c);
  const double bright = mean_brightness(full), dim = mean_brightness(lamps);
  EXPECT_GT(bright, 20);
  EXPECT_LT(dim, 0.8 * bright);
  EXPECT_GT(dim, 5);  // ambient light still shows the room
}

TEST(Render, ATileRendersTheSameWhateverElseIsInThePass) {
  EnvConfig c = test::box_room_config();
  c.start_jitter = 0.1;
  Env a(c), b(c), e(c);
  a.reset(0);
  b.reset(1);
  e.reset(2);
  std::vector<Env*> envs = {&a, &b, &e};
  // Each env alone in its tile, then all three in one pass: the same pixels.
  ArrayDict alone(a.observation_space(), 3), together(a.observation_space(), 3);
  Renderer renderer(a.world().model(), 128, 128, 4);
  std::vector<CameraView> pass;
  for (int i = 0; i < 3; ++i) {
    std::vector<CameraView> views = envs[i]->impl().camera_views(alone, i);
    for (CameraView& v : views) v.tile = i + 1;
    renderer.render(views);
    for (CameraView& v : envs[i]->impl().camera_views(together, i)) {
      v.tile = i + 1;
      pass.push_back(v);
    }
  }
  renderer.render(pass);
  EXPECT_EQ(alone["rgb"].bytes, together["rgb"].bytes);
  EXPECT_EQ(alone["depth"].bytes, together["depth"].bytes);
  // The robots stand at different (seeded) poses: different images.
  EXPECT_NE(std::memcmp(alone["rgb"].item(0), alone["rgb"].item(1), alone["rgb"].item_bytes()), 0);
  // Tile 0 of a wide buffer equals a one-tile renderer's image.
  Renderer single(a.world().model(), 128, 128, 1);
  ArrayDict one(a.observation_space(), 1);
  single.render(a.impl().camera_views(one, 0));
  std::vector<CameraView> first = a.impl().camera_views(together, 0);
  renderer.render(first);
  EXPECT_EQ(std::memcmp(one["rgb"].item(0), together["rgb"].item(0), one["rgb"].item_bytes()), 0);
}

// Tiles fill rows of the offscreen buffer (8192 pixels wide: 64 tiles of
// 128): tile 64 starts the second row. A pass spanning both rows reads back
// each tile's own pixels, as a pass of that tile alone does.
TEST(Render, TilesFillRowsOfTheBufferAndEachReadsBackItsOwn) {
  EnvConfig c = test::box_room_config();
  c.start_jitter = 0.1;
  Env a(c), b(c);
  a.reset(0);
  b.reset(1);
  Renderer renderer(a.world().model(), 128, 128, 66);
  EXPECT_EQ(Renderer::tile_capacity(128, 128), 64 * 64);
  ArrayDict alone(a.observation_space(), 2), together(a.observation_space(), 2);
  const auto views = [](Env& env, ArrayDict& obs, int index, int tile) {
    std::vector<CameraView> out = env.impl().camera_views(obs, index);
    for (CameraView& v : out) v.tile = tile;
    return out;
  };
  renderer.render(views(a, alone, 0, 3));
  renderer.render(views(b, alone, 1, 65));
  std::vector<CameraView> pass = views(a, together, 0, 3), second = views(b, together, 1, 65);
  pass.insert(pass.end(), second.begin(), second.end());
  renderer.render(pass);
  EXPECT_EQ(alone["rgb"].bytes, together["rgb"].bytes);
  EXPECT_EQ(alone["depth"].bytes, together["depth"].bytes);
  EXPECT_NE(std::memcmp(alone["rgb"].item(0), alone["rgb"].item(1), alone["rgb"].item_bytes()), 0);
  const Array& rgb = alone["rgb"];
  EXPECT_GT(std::set<unsigned char>(rgb.bytes.begin() + rgb.item_bytes(), rgb.bytes.end()).size(), 20u)
      << "the second row's tile is drawn";
  EXPECT_EQ(test::error_of([&] { Renderer too_many(a.world().model(), 128, 128, 64 * 64 + 1); }),
            "renderer: 4097 tiles of 128x128 exceed the 8192x8192 offscreen buffer");
}

TEST(Render, ApartmentPictures) {
  EnvConfig c;
  c.width = c.height = 256;
  Env env(c);
  auto r = env.reset(0);
  save_png(r.obs["rgb"], 0, 256, 256, "apartment_head_camera.png");
  // The whole apartment from above, ceilings left out (docs/images/).
  Renderer top(env.world().model(), 512, 512, 1);
  ArrayDict overview(Space::dict({{"rgb", Space::box({512, 512, 3}, DType::uint8, 0, 255)}}), 1);
  std::vector<CameraView> view = {{env.world().model(), env.impl().world().data(),
                                   env.world().scene().overview_camera(),
                                   static_cast<std::uint8_t*>(overview["rgb"].item(0)), nullptr, 0, false}};
  top.render(view);
  save_png(overview["rgb"], 0, 512, 512, "apartment_overview.png");
  // From above, the floors of the rooms show, not the ceiling's single colour.
  std::set<int> top_colours;
  for (size_t i = 0; i + 2 < overview["rgb"].bytes.size(); i += 3) {
    const auto& b = overview["rgb"].bytes;
    top_colours.insert((b[i] >> 4) << 8 | (b[i + 1] >> 4) << 4 | b[i + 2] >> 4);
  }
  EXPECT_GT(top_colours.size(), 50u);
  // A furnished room is not a flat image: many distinct colours.
  const Array& rgb = r.obs["rgb"];
  std::set<int> colours;
  for (size_t i = 0; i + 2 < rgb.bytes.size(); i += 3) {
    colours.insert((rgb.bytes[i] >> 4) << 8 | (rgb.bytes[i + 1] >> 4) << 4 | rgb.bytes[i + 2] >> 4);
  }
  EXPECT_GT(colours.size(), 20u);
}

}  // namespace
}  // namespace chore
