// `chore plot`: learning curves from constructed metrics.csv files, checked
// pixel by pixel where the curves must be.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "app/plot.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

constexpr const char* kHeader = "env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length,update_ms\n";

// A run whose mean_q is q(step), logged every 1000 steps up to 30000.
std::string run(const std::function<double(double)>& q) {
  std::string text = kHeader;
  for (int step = 0; step <= 30000; step += 1000) {
    text += std::to_string(step) + ",1.5,3,0.5," + std::to_string(q(step)) + ",0.1,12,40\n";
  }
  return text;
}

// The colour at a data point, from the frame plot_curves reports.
cv::Vec3b at(const cv::Mat& image, const nlohmann::json& frame, double x, double y) {
  const auto& a = frame["area"];
  const double x0 = frame["x_range"][0], x1 = frame["x_range"][1], y0 = frame["y_range"][0], y1 = frame["y_range"][1];
  const int col = a[0].get<int>() + static_cast<int>(std::lround((x - x0) / (x1 - x0) * a[2].get<int>()));
  const int row = a[1].get<int>() + static_cast<int>(std::lround((y1 - y) / (y1 - y0) * a[3].get<int>()));
  return image.at<cv::Vec3b>(row, col);
}

TEST(Plot, GroupsRunsByLabelWithMeanAndSpread) {
  const auto dir = test::scratch_dir("plot");
  // Method "ppo": two seeds at 0.8 and 0.6 (mean 0.7, std 0.1); "sac": one run rising 0 -> 0.3.
  test::write_file(dir / "ppo_seed0" / "metrics.csv", run([](double) { return 0.8; }));
  test::write_file(dir / "ppo_seed1" / "metrics.csv", run([](double) { return 0.6; }));
  test::write_file(dir / "other" / "metrics.csv", run([](double s) { return 0.3 * s / 30000; }));
  PlotOptions options;
  options.runs = {(dir / "ppo_seed0/metrics.csv").string(), (dir / "ppo_seed1/metrics.csv").string(),
                  "sac=" + (dir / "other/metrics.csv").string()};
  options.y = "mean_q";
  options.out = (test::output_dir() / "plot_curves.png").string();
  const nlohmann::json r = plot_curves(options);
  ASSERT_EQ(r["groups"].size(), 2u);
  EXPECT_EQ(r["groups"][0]["label"], "ppo");
  EXPECT_EQ(r["groups"][0]["runs"], 2);
  EXPECT_EQ(r["groups"][1]["label"], "sac");
  EXPECT_EQ(r["groups"][1]["runs"], 1);

  const cv::Mat image = cv::imread(options.out);
  ASSERT_EQ(image.cols, 960);
  ASSERT_EQ(image.rows, 600);
  const cv::Vec3b blue(180, 119, 31), orange(14, 127, 255), white(255, 255, 255);
  const auto near = [](cv::Vec3b a, cv::Vec3b b, int tolerance) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) <= tolerance;
  };
  // ppo's mean line at 0.7; its band (blue, a quarter opaque) at 0.75; nothing at 0.85.
  EXPECT_TRUE(near(at(image, r, 20000, 0.7), blue, 60)) << at(image, r, 20000, 0.7);
  const cv::Vec3b band = at(image, r, 20000, 0.75);
  EXPECT_FALSE(near(band, white, 30)) << band;
  EXPECT_TRUE(band[0] > band[2] && band[0] > 200) << band;  // bluish, light
  EXPECT_TRUE(near(at(image, r, 20000, 0.85), white, 30) ||
              near(at(image, r, 20000, 0.85), cv::Vec3b(228, 228, 228), 30));
  // sac's line passes 0.2 at 20000 steps.
  EXPECT_TRUE(near(at(image, r, 20000, 0.2), orange, 60)) << at(image, r, 20000, 0.2);
  EXPECT_TRUE(near(at(image, r, 10000, 0.1), orange, 60)) << at(image, r, 10000, 0.1);
}

TEST(Plot, TheBandStaysWithinTheRunsValues) {
  // Q of 0, 0 and 0.9: mean 0.3, std 0.42; mean - std would be -0.12, a Q no run had.
  const auto dir = test::scratch_dir("plot_band");
  for (const auto& [name, q] : {std::pair{"a_seed0", 0.0}, {"a_seed1", 0.0}, {"a_seed2", 0.9}}) {
    test::write_file(dir / name / "metrics.csv", run([q = q](double) { return q; }));
  }
  PlotOptions options;
  for (const char* name : {"a_seed0", "a_seed1", "a_seed2"})
    options.runs.push_back((dir / name / "metrics.csv").string());
  options.y = "mean_q";
  options.out = (test::output_dir() / "plot_band.png").string();
  const nlohmann::json r = plot_curves(options);
  // The y axis spans the band, 0 to 0.72 (0.3 + 0.42), plus 5% of that each side.
  const double high = 0.3 + std::sqrt(0.18), pad = 0.05 * high;
  EXPECT_NEAR(r["y_range"][0].get<double>(), -pad, 1e-9);
  EXPECT_NEAR(r["y_range"][1].get<double>(), high + pad, 1e-9);
}

// The legend takes the corner the curves leave emptiest: top left beside a
// rising curve, elsewhere beside a falling one (a performance profile).
TEST(Plot, TheLegendLeavesTheCurvesVisible) {
  const auto dir = test::scratch_dir("plot_legend");
  test::write_file(dir / "rising" / "metrics.csv", run([](double s) { return s / 30000; }));
  test::write_file(dir / "falling" / "metrics.csv", run([](double s) { return 1 - s / 30000; }));
  const auto legend = [&](const std::string& name) {
    PlotOptions options;
    options.runs = {(dir / name / "metrics.csv").string()};
    options.y = "mean_q";
    options.out = (test::output_dir() / ("plot_legend_" + name + ".png")).string();
    const nlohmann::json r = plot_curves(options);
    const auto& a = r["area"];
    const auto& l = r["legend"];
    EXPECT_GE(l[0].get<int>(), a[0].get<int>());
    EXPECT_LE(l[0].get<int>() + l[2].get<int>(), a[0].get<int>() + a[2].get<int>());
    return std::pair(l[0].get<int>() - a[0].get<int>(), l[1].get<int>() - a[1].get<int>());  // offset in the axes
  };
  EXPECT_EQ(legend("rising"), std::pair(10, 10));
  const auto [x, y] = legend("falling");  // the top left holds the curve's start: the top right is empty
  EXPECT_GT(x, 10);
  EXPECT_EQ(y, 10);
}

TEST(Plot, BadFilesAreErrorsNamingThem) {
  const auto dir = test::scratch_dir("plot_errors");
  PlotOptions options;
  options.out = (dir / "x.png").string();
  options.runs = {(dir / "missing.csv").string()};
  EXPECT_EQ(test::error_of([&] { plot_curves(options); }), options.runs[0] + ": no such file; expected a metrics.csv");
  test::write_file(dir / "a" / "metrics.csv", std::string(kHeader) + "100,1,1,0.5,0.5,0,1,3\n200,1,1,oops,0.5,0,1,3\n");
  options.runs = {(dir / "a/metrics.csv").string()};
  EXPECT_EQ(test::error_of([&] { plot_curves(options); }),
            "plot: " + options.runs[0] + ":3: 'oops' in column 'success_rate' is not a number");
  options.y = "reward";
  EXPECT_NE(test::error_of([&] { plot_curves(options); }).find("has no column 'reward'"), std::string::npos);
}

}  // namespace
}  // namespace chore
