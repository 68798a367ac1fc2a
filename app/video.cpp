#include "app/video.hpp"

#include <cstdio>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "base/error.hpp"
#include "world/renderer.hpp"

namespace chore {
namespace {

constexpr int kCaptionHeight = 44;

// What step `step` did, in words: the primitive and its outcome, or the first
// low-level action values.
std::string describe_action(const EnvState& env, std::span<const float> action, const Info& info) {
  if (!env.primitive_actions().empty()) {
    const std::string outcome =
        info.primitive_status >= 0 ? to_string(static_cast<PrimitiveStatus>(info.primitive_status)) : "-";
    return to_string(env.primitive_actions()[static_cast<size_t>(action[0])]) + " -> " + outcome;
  }
  std::string text = "action [";
  char value[16];
  for (size_t i = 0; i < std::min<size_t>(action.size(), 6); ++i) {
    std::snprintf(value, sizeof value, "%s%+.2f", i ? " " : "", action[i]);
    text += value;
  }
  return text + (action.size() > 6 ? " ...]" : "]");
}

}  // namespace

nlohmann::json record_video(const PolicySource& source, const VideoOptions& options, std::ostream& log) {
  if (options.out.empty()) throw Error("video: --out FILE.mp4 is required");
  if (options.size < 16 || options.size > 2048) throw Error("video: --size must be in 16..2048");
  if (options.fps < 0) throw Error("video: --fps must be positive");
  VectorEnvConfig config;
  config.env = source.env;
  VectorEnv envs(config);
  const EnvState& env = envs.state(0);
  const std::unique_ptr<Policy> policy = source.make(envs);
  const bool primitives = !env.primitive_actions().empty();
  const double fps = options.fps > 0 ? options.fps : primitives ? 2.0 : 30.0;
  const int size = options.size;
  const cv::Size frame_size(2 * size, size + kCaptionHeight);
  // H.264 plays everywhere (browsers too); MPEG-4 Part 2 where it cannot be had.
  std::string codec;
  cv::VideoWriter writer;
  for (const char* c : {"avc1", "mp4v"}) {
    if (writer.open(options.out, cv::CAP_FFMPEG, cv::VideoWriter::fourcc(c[0], c[1], c[2], c[3]), fps, frame_size)) {
      codec = c;
      break;
    }
  }
  if (!writer.isOpened()) throw Error("video: cannot write '" + options.out + "' (avc1 or mp4v, OpenCV's FFmpeg)");

  // Both views in one pass of this thread's renderer; rows come top first.
  Renderer renderer(env.world().model(), size, size, 2);
  cv::Mat head(size, size, CV_8UC3), top(size, size, CV_8UC3), frame(frame_size, CV_8UC3);
  const auto write_frame = [&](const std::string& line1, const std::string& line2) {
    // mjv_updateScene takes mjData non-const; it does not change it.
    auto* data = const_cast<mjData_*>(env.world().data());
    const Scene& scene = env.world().scene();
    const std::vector<CameraView> views = {
        {env.world().model(), data, scene.camera(), head.data, nullptr, 0, true, &env.world()},
        {env.world().model(), data, scene.overview_camera(), top.data, nullptr, 1, false, &env.world()}};
    renderer.render(views);
    frame.setTo(cv::Scalar(255, 255, 255));
    cv::cvtColor(head, frame(cv::Rect(0, 0, size, size)), cv::COLOR_RGB2BGR);
    cv::cvtColor(top, frame(cv::Rect(size, 0, size, size)), cv::COLOR_RGB2BGR);
    const double scale = std::min(0.5, 0.5 * size / 256.0);
    cv::putText(frame, line1, {6, size + 18}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    cv::putText(frame, line2, {6, size + 38}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    writer.write(frame);
  };
  const auto scores = [](double reward, const Info& info) {
    char text[128];
    std::snprintf(text, sizeof text, "reward %+.3f   Q %.2f (%d/%d goal literals)", reward, info.q, info.satisfied,
                  info.total);
    return std::string(text);
  };

  Batch batch = envs.reset(options.seed);
  const std::vector<int> ids = {0};
  policy->reset(ids);
  write_frame("step 0 (start, seed " + std::to_string(options.seed) + ")", scores(0, batch.infos[0]));
  std::vector<float> action(std::max<size_t>(1, envs.single_action_space().element_count()));
  int frames = 1, steps = 0;
  for (bool done = false; !done;) {
    policy->act(batch, action);
    batch = envs.step(action);
    const Info& info = batch.infos[0];
    ++steps;
    done = batch.terminated[0] || batch.truncated[0];
    std::string status = done ? (info.success          ? "  [success]"
                                 : info.policy_failure ? "  [policy failure]"
                                                       : "  [end]")
                              : "";
    write_frame("step " + std::to_string(steps) + "  " + describe_action(env, action, info) + status,
                scores(batch.rewards[0], info));
    ++frames;
    if (steps % 10 == 0) log << "video: " << steps << " steps\n";
  }
  writer.release();
  const Info& last = batch.infos[0];
  return {{"out", options.out},
          {"frames", frames},
          {"width", frame_size.width},
          {"height", frame_size.height},
          {"fps", fps},
          {"codec", codec},
          {"steps", steps},
          {"success", last.success},
          {"q", last.q}};
}

}  // namespace chore
