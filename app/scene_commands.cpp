#include "app/scene_commands.hpp"

#include <mujoco/mujoco.h>

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "analogs/scene_analogs.hpp"
#include "app/png.hpp"
#include "world/renderer.hpp"
#include "world/scene.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void list_scenes(std::ostream& out) {
  for (const SceneInventory& s : shipped_scene_inventories()) {
    std::string types;
    for (const RoomInventory& r : s.rooms) types += (types.empty() ? "" : " ") + r.name;
    out << s.name << ": " << s.rooms.size() << " rooms, " << s.object_count() << " objects (" << types << ")\n";
  }
}

nlohmann::json build_scene(const SceneBuildOptions& o) {
  const SceneInventory& inventory = find_scene_inventory(o.name);
  auto start = std::chrono::steady_clock::now();
  const SceneAnalog analog = generate_scene_analog(inventory, *CategoryModels::shipped(), o.seed);
  const double generate_s = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const auto scene = Scene::build(analog.file, {.model_cache = o.model_cache});
  const double compile_s = seconds_since(start);
  double x1 = 0, y1 = 0;
  for (const Room& r : analog.file.rooms) {
    for (const auto& rect : r.rects) x1 = std::max(x1, rect[2]), y1 = std::max(y1, rect[3]);
  }
  nlohmann::json result = {{"scene", o.name},
                           {"seed", o.seed},
                           {"rooms", analog.file.rooms.size()},
                           {"size_m", {x1, y1}},
                           {"inventory_objects", inventory.object_count()},
                           {"placed", analog.placed},
                           {"left_out", analog.left_out},
                           {"models", analog.file.models.size()},
                           {"bodies", scene->model()->nbody},
                           {"geoms", scene->model()->ngeom},
                           {"generate_s", generate_s},
                           {"compile_s", compile_s},
                           {"from_cache", scene->from_cache()}};
  if (!o.out.empty()) {
    constexpr int kSize = 1024;
    World world(scene);
    world.reset(scene->robot_start());
    Renderer top(scene->model(), kSize, kSize);
    std::vector<std::uint8_t> rgb(3 * kSize * kSize);
    std::vector<CameraView> view = {
        {scene->model(), world.data(), scene->overview_camera(), rgb.data(), nullptr, 0, false, &world}};
    top.render(view);
    cv::Mat bgr;
    cv::cvtColor(cv::Mat(kSize, kSize, CV_8UC3, rgb.data()), bgr, cv::COLOR_RGB2BGR);
    write_png(o.out, bgr, "scene build");
    result["picture"] = o.out;
  }
  return result;
}

std::string format_scene_build(const nlohmann::json& r) {
  std::ostringstream s;
  s.precision(3);
  s << "scene " << r["scene"].get<std::string>() << " (analog, seed " << r["seed"] << "): " << r["rooms"] << " rooms, "
    << r["size_m"][0].get<double>() << " x " << r["size_m"][1].get<double>() << " m; " << r["placed"] << " of "
    << r["inventory_objects"] << " inventory objects placed (" << r["left_out"] << " left out), " << r["models"]
    << " models; " << r["bodies"] << " bodies, " << r["geoms"] << " geoms; generated in "
    << r["generate_s"].get<double>() << " s, "
    << (r["from_cache"].get<bool>() ? "loaded from the model cache in " : "compiled in ")
    << r["compile_s"].get<double>() << " s";
  if (r.contains("picture")) s << "; picture: " << r["picture"].get<std::string>();
  return s.str() + "\n";
}

}  // namespace chore
