#include "app/activity_commands.hpp"

#include <chrono>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/png.hpp"
#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "tasks/activity.hpp"
#include "world/renderer.hpp"

namespace chore {

int check_activities(const std::vector<std::string>& files, std::ostream& out, std::ostream& err) {
  const Vocabulary vocabulary = load_vocabulary();
  int failed = 0;
  for (const std::string& file : files) {
    try {
      const auto [p, goal] = check_activity(file, vocabulary);
      size_t literals = 0;
      for (const GroundOption& o : goal.options) literals = std::max(literals, o.size());
      out << file << ": " << p.name << " (" << to_string(p.domain) << "): " << p.objects.size() << " objects, "
          << p.init.size() << " initial literals, " << goal.conditions.size() << " goal conditions, "
          << goal.options.size() << " ground options of up to " << literals << " literals (" << goal.literals.size()
          << " distinct)\n";
    } catch (const Error& e) {
      err << "chore: error: " << e.what() << std::endl;
      ++failed;
    }
  }
  return failed;
}

namespace {

cv::Mat to_bgr(const Array& rgb, int height, int width) {
  cv::Mat image(height, width, CV_8UC3, const_cast<void*>(rgb.item(0)));
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

}  // namespace

cv::Mat instance_picture(Env& env, const ArrayDict& obs, int head_size, int top_size) {
  // The third-person view: the whole scene from above, ceilings left out.
  Renderer top(env.world().model(), top_size, top_size);
  ArrayDict overview(Space::dict({{"rgb", Space::box({top_size, top_size, 3}, DType::uint8, 0, 255)}}), 1);
  std::vector<CameraView> view = {
      {env.world().model(), env.impl().world().data(), env.world().scene().overview_camera(),
       static_cast<std::uint8_t*>(overview["rgb"].item(0)), nullptr, 0, false, &env.world()}};
  top.render(view);
  cv::Mat head = to_bgr(obs["rgb"], head_size, head_size);
  cv::Mat panel(top_size, head_size + top_size, CV_8UC3, cv::Scalar(0, 0, 0));
  head.copyTo(panel(cv::Rect(0, (top_size - head_size) / 2, head_size, head_size)));
  to_bgr(overview["rgb"], top_size, top_size).copyTo(panel(cv::Rect(head_size, 0, top_size, top_size)));
  return panel;
}

void sample_activity(const std::string& activity, const std::string& scene, uint64_t seed, const std::string& png,
                     std::ostream& out) {
  constexpr int kHead = 384, kTop = 768;
  EnvConfig config;
  config.activity = activity;
  config.scene = scene;
  config.width = config.height = kHead;
  config.observations = {"rgb"};
  config.reachable_instances = false;  // the instance as sampled: what is out of reach is said below
  Env env(config);
  out << activity << " in " << env.world().scene().name() << " (" << env.world().scene().objects().size()
      << " objects): instantiating seed " << seed << std::endl;
  const auto reset = env.reset(seed);
  const std::string out_of_reach = env.out_of_reach();
  write_png(png, instance_picture(env, reset.obs, kHead, kTop), "activity sample");
  out << activity << " seed " << seed << " in " << env.world().scene().name() << ": Q " << reset.info.q << ", "
      << reset.info.satisfied << "/" << reset.info.total << " goal literals hold; "
      << (out_of_reach.empty() ? "what a plan for the goal acts on is within the robot's reach"
                               : "out of the robot's reach: " + out_of_reach)
      << "; picture: " << png << "\n";
}

void sample_activity_seeds(const std::string& activity, const std::string& scene, uint64_t first, uint64_t last,
                           std::ostream& out) {
  EnvConfig config;
  config.activity = activity;
  config.scene = scene;
  config.observations = {"proprio"};
  Env env(config);
  // Said first: an activity of hundreds of objects takes seconds an instance,
  // and a seed up to Env::kInstanceAttempts instances.
  out << activity << " in " << env.world().scene().name() << " (" << env.world().scene().objects().size()
      << " objects): instantiating seeds " << first << "-" << last << ", each resampled up to "
      << Env::kInstanceAttempts << " times until what a plan for the goal acts on is within the robot's reach"
      << std::endl;
  const auto start = std::chrono::steady_clock::now();
  for (uint64_t seed = first; seed <= last; ++seed) env.impl().reset_state(seed);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out << activity << " in " << env.world().scene().name() << ": seeds " << first << "-" << last << " all instantiated ("
      << (last - first + 1) << "), " << 1000 * seconds / (last - first + 1) << " ms each\n";
}

}  // namespace chore
