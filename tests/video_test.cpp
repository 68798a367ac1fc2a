// `chore video`: an expert episode recorded to MP4 reads back with the
// expected frame count, size and content.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "app/video.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

TEST(Video, AnExpertEpisodeReadsBackFrameByFrame) {
  VideoOptions options;
  options.seed = 1;
  options.size = 160;
  options.out = (test::scratch_dir("video") / "expert.mp4").string();
  std::ostringstream log;
  const nlohmann::json r = record_video(expert_source("store_decoration", ExecutionMode::symbolic, 60), options, log);
  // The expert stores both pumpkins in 10 primitives (Primitives.TheExpertStoresBothPumpkinsInTheRightOrder):
  // the first observation and one frame per primitive.
  EXPECT_EQ(r["steps"].get<int>(), 10);
  EXPECT_TRUE(r["success"].get<bool>());
  EXPECT_EQ(r["frames"].get<int>(), 11);

  cv::VideoCapture video(options.out);
  ASSERT_TRUE(video.isOpened());
  std::vector<cv::Mat> frames;
  for (cv::Mat f; video.read(f);) frames.push_back(f.clone());
  ASSERT_EQ(frames.size(), 11u);
  for (const cv::Mat& f : frames) {
    EXPECT_EQ(f.cols, 2 * 160);
    EXPECT_EQ(f.rows, 160 + 44);  // the views over the caption strip
  }
  // Not black, not flat: both views have texture, and the caption is dark text on white.
  for (const cv::Mat& f : {frames.front(), frames.back()}) {
    for (const cv::Rect view : {cv::Rect(0, 0, 160, 160), cv::Rect(160, 0, 160, 160)}) {
      cv::Scalar mean, stddev;
      cv::meanStdDev(f(view), mean, stddev);
      EXPECT_GT(mean[0] + mean[1] + mean[2], 3 * 30.0);
      EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 3 * 10.0);
    }
    cv::Mat caption;
    cv::cvtColor(f(cv::Rect(0, 160, 320, 44)), caption, cv::COLOR_BGR2GRAY);
    EXPECT_GT(cv::countNonZero(caption < 100), 50);    // text
    EXPECT_GT(cv::countNonZero(caption > 200), 5000);  // background
  }
  // The robot moved: the head camera sees something else at the end.
  cv::Mat difference;
  cv::absdiff(frames.front()(cv::Rect(0, 0, 160, 160)), frames.back()(cv::Rect(0, 0, 160, 160)), difference);
  EXPECT_GT(cv::mean(difference)[0] + cv::mean(difference)[1] + cv::mean(difference)[2], 3 * 10.0);
  cv::imwrite((test::output_dir() / "video_first_frame.png").string(), frames.front());
  cv::imwrite((test::output_dir() / "video_last_frame.png").string(), frames.back());
}

// A low-level policy: turn in place. One frame per 1/30 s step, at 30 frames/s.
class TurnInPlace : public Policy {
  void act(const Batch& batch, std::span<float> actions) override {
    std::fill(actions.begin(), actions.end(), 0.f);
    for (int row = 0; row < batch.size(); ++row) actions[row * kLowLevelActionSize + 2] = 1.f;
  }
};

TEST(Video, LowLevelStepsAreRealTime) {
  EnvConfig env;
  env.activity = "store_decoration";
  env.observations = {"proprio"};
  env.max_episode_steps = 12;
  const PolicySource turn{"turn", env, [](const VectorEnv&) { return std::make_unique<TurnInPlace>(); }};
  VideoOptions options;
  options.size = 64;
  options.out = (test::scratch_dir("video_low_level") / "turn.mp4").string();
  std::ostringstream log;
  const nlohmann::json r = record_video(turn, options, log);
  EXPECT_EQ(r["frames"].get<int>(), 13);
  EXPECT_EQ(r["fps"].get<double>(), 30.0);
  cv::VideoCapture video(options.out);
  int frames = 0;
  for (cv::Mat f; video.read(f);) ++frames;
  EXPECT_EQ(frames, 13);
}

TEST(Video, AnUnwritablePathIsAnError) {
  VideoOptions options;
  options.out = "/no/such/dir/x.mp4";
  std::ostringstream log;
  EXPECT_NE(test::error_of([&] {
              record_video(expert_source("store_decoration", ExecutionMode::symbolic, 60), options, log);
            }).find("video: cannot write '/no/such/dir/x.mp4'"),
            std::string::npos);
}

}  // namespace
}  // namespace chore
