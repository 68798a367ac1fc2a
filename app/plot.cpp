#include "app/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/png.hpp"
#include "base/error.hpp"
#include "base/input_file.hpp"

namespace chore {
namespace {

constexpr int kGridPoints = 200;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0), kGrey(120, 120, 120), kGridLine(228, 228, 228), kWhite(255, 255, 255);
// Matplotlib's tab10, BGR.
const cv::Scalar kColours[] = {{180, 119, 31}, {14, 127, 255},  {44, 160, 44},   {40, 39, 214},  {189, 103, 148},
                               {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23}};

struct Curve {
  std::vector<double> x, y;
};

struct Group {
  std::string label;
  std::vector<Curve> runs;
  Curve mean, low, high;  // high - mean = mean - low = std
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// A run's metrics.csv is a row per rollout: ~50 KB for the baselines' 30,000 steps.
constexpr size_t kMaxMetricsBytes = 256u << 20;

// The x and y columns of a metrics.csv; rows with an empty or nan y are skipped.
Curve read_run(const std::string& path, const std::string& x, const std::string& y) {
  std::istringstream in(read_text_file(path, kMaxMetricsBytes, "a metrics.csv"));
  std::string line;
  if (!std::getline(in, line)) throw Error("plot: '" + path + "' is empty (expected a header row)");
  const std::vector<std::string> header = split(line);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw Error("plot: '" + path + "' has no column '" + name + "' (header: " + line + ")");
    return static_cast<size_t>(it - header.begin());
  };
  const size_t cx = column(x), cy = column(y);
  Curve c;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    const auto value = [&](size_t k) {
      const std::string cell = k < cells.size() ? cells[k] : "";
      try {
        size_t used = 0;
        const double v = std::stod(cell, &used);
        if (used == cell.size()) return v;
      } catch (const std::exception&) {
      }
      throw Error("plot: " + path + ":" + std::to_string(number) + ": '" + cell + "' in column '" + header[k] +
                  "' is not a number");
    };
    if (cy >= cells.size() || cells[cy].empty() || cells[cy] == "nan") continue;
    const double vx = value(cx), vy = value(cy);
    if (!c.x.empty() && vx < c.x.back()) {
      throw Error("plot: " + path + ":" + std::to_string(number) + ": column '" + x + "' goes backwards");
    }
    c.x.push_back(vx);
    c.y.push_back(vy);
  }
  if (c.x.empty()) throw Error("plot: '" + path + "' has no rows with a value of '" + y + "'");
  return c;
}

// "LABEL=path" or the run directory's name less a seed suffix.
std::pair<std::string, std::string> label_and_path(const std::string& run) {
  const auto eq = run.find('=');
  if (eq != std::string::npos && eq > 0 && run.substr(0, eq).find('/') == std::string::npos) {
    return {run.substr(0, eq), run.substr(eq + 1)};
  }
  const std::filesystem::path path(run);
  std::string dir = path.parent_path().filename().string();
  if (dir.empty()) dir = path.stem().string();
  // NAME[_-]seed[_-]DIGITS -> NAME (rl-prim_seed3 -> rl-prim).
  size_t end = dir.size();
  while (end > 0 && dir[end - 1] >= '0' && dir[end - 1] <= '9') --end;
  if (end < dir.size() && end > 0 && (dir[end - 1] == '_' || dir[end - 1] == '-')) --end;
  if (end < dir.size() && end > 4 && dir.compare(end - 4, 4, "seed") == 0) {
    end -= 4;
    if (end > 1 && (dir[end - 1] == '_' || dir[end - 1] == '-')) --end;
    dir.resize(end);
  }
  return {dir, run};
}

double interpolate(const Curve& c, double x) {
  const auto it = std::lower_bound(c.x.begin(), c.x.end(), x);
  if (it == c.x.begin()) return c.y.front();
  if (it == c.x.end()) return c.y.back();
  const size_t i = it - c.x.begin();
  const double t = (x - c.x[i - 1]) / std::max(1e-300, c.x[i] - c.x[i - 1]);
  return c.y[i - 1] + t * (c.y[i] - c.y[i - 1]);
}

void summarise(Group& g) {
  if (g.runs.size() == 1) {
    g.mean = g.low = g.high = g.runs[0];
    return;
  }
  double from = -INFINITY, to = INFINITY;
  for (const Curve& r : g.runs) {
    from = std::max(from, r.x.front());
    to = std::min(to, r.x.back());
  }
  if (to < from) throw Error("plot: the runs of '" + g.label + "' share no x range");
  for (int i = 0; i < kGridPoints; ++i) {
    const double x = to > from ? from + (to - from) * i / (kGridPoints - 1) : from;
    double sum = 0, squares = 0, lowest = INFINITY, highest = -INFINITY;
    for (const Curve& r : g.runs) {
      const double y = interpolate(r, x);
      sum += y;
      lowest = std::min(lowest, y);
      highest = std::max(highest, y);
    }
    const double mean = sum / g.runs.size();
    for (const Curve& r : g.runs) squares += std::pow(interpolate(r, x) - mean, 2);
    const double std = std::sqrt(squares / g.runs.size());
    // The band stays within the runs' values: a Q of 0, 0, 0.9 draws no band below 0.
    for (auto [curve, y] :
         {std::pair{&g.mean, mean}, {&g.low, std::max(mean - std, lowest)}, {&g.high, std::min(mean + std, highest)}}) {
      curve->x.push_back(x);
      curve->y.push_back(y);
    }
  }
}

// Round tick spacing (1, 2 or 5 times a power of ten) for about `count` ticks.
double tick_step(double span, int count) {
  const double raw = span / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (raw <= m * power) return m * power;
  }
  return 10 * power;
}

// A tick label; an axis reaching 10,000 counts in thousands ("25k").
std::string number(double v, bool thousands) {
  char text[32];
  if (std::abs(v) < 1e-12) v = 0;
  std::snprintf(text, sizeof text, thousands && v != 0 ? "%gk" : "%g", thousands ? v / 1000 : v);
  return text;
}

}  // namespace

nlohmann::json plot_curves(const PlotOptions& options) {
  if (options.runs.empty()) throw Error("plot: give one or more metrics.csv files");
  if (options.out.empty()) throw Error("plot: --out FILE.png is required");
  if (options.width < 320 || options.height < 240) throw Error("plot: the picture must be at least 320x240");
  std::vector<Group> groups;
  for (const std::string& run : options.runs) {
    const auto [label, path] = label_and_path(run);
    auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.label == label; });
    if (g == groups.end()) g = groups.insert(groups.end(), Group{label, {}, {}, {}, {}});
    g->runs.push_back(read_run(path, options.x, options.y));
  }
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (Group& g : groups) {
    summarise(g);
    x0 = std::min(x0, g.mean.x.front());
    x1 = std::max(x1, g.mean.x.back());
    for (double v : g.low.y) y0 = std::min(y0, v);
    for (double v : g.high.y) y1 = std::max(y1, v);
  }
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 - y0 < 1e-9) {
    y0 -= 0.5;
    y1 += 0.5;
  }
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad;
  y1 += pad;

  const int left = 90, right = 24, top = 48, bottom = 70;
  const cv::Rect area(left, top, options.width - left - right, options.height - top - bottom);
  const auto px = [&](double x, double y) {
    return cv::Point2d(area.x + (x - x0) / (x1 - x0) * area.width, area.y + (y1 - y) / (y1 - y0) * area.height);
  };
  cv::Mat image(options.height, options.width, CV_8UC3, kWhite);
  const int shift = 4;  // sub-pixel drawing: coordinates in 1/16 pixel
  const auto fixed = [&](cv::Point2d p) { return cv::Point(cvRound(p.x * (1 << shift)), cvRound(p.y * (1 << shift))); };

  // Grid and tick labels.
  const auto centred = [&](const std::string& text, cv::Point at, double scale) {
    int base = 0;
    const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &base);
    cv::putText(image, text, {at.x - size.width / 2, at.y + size.height / 2}, kFont, scale, kBlack, 1, cv::LINE_AA);
  };
  const double xs = tick_step(x1 - x0, 6), ys = tick_step(y1 - y0, 6);
  for (double x = std::ceil(x0 / xs) * xs; x <= x1 + 1e-9 * xs; x += xs) {
    const cv::Point p = px(x, y0);
    cv::line(image, {p.x, area.y}, {p.x, area.y + area.height}, kGridLine, 1);
    cv::line(image, {p.x, area.y + area.height}, {p.x, area.y + area.height + 5}, kBlack, 1);
    centred(number(x, x1 >= 1e4), {p.x, area.y + area.height + 18}, 0.45);
  }
  for (double y = std::ceil(y0 / ys) * ys; y <= y1 + 1e-9 * ys; y += ys) {
    const cv::Point p = px(x0, y);
    cv::line(image, {area.x, p.y}, {area.x + area.width, p.y}, kGridLine, 1);
    cv::line(image, {area.x - 5, p.y}, {area.x, p.y}, kBlack, 1);
    int base = 0;
    const std::string text = number(y, y1 >= 1e4);
    const cv::Size size = cv::getTextSize(text, kFont, 0.45, 1, &base);
    cv::putText(image, text, {area.x - 9 - size.width, p.y + size.height / 2}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }

  // Bands (a quarter opaque), then the mean lines over them.
  for (size_t k = 0; k < groups.size(); ++k) {
    const Group& g = groups[k];
    if (g.runs.size() < 2) continue;
    std::vector<cv::Point> band;
    for (size_t i = 0; i < g.high.x.size(); ++i) band.push_back(fixed(px(g.high.x[i], g.high.y[i])));
    for (size_t i = g.low.x.size(); i-- > 0;) band.push_back(fixed(px(g.low.x[i], g.low.y[i])));
    cv::Mat layer = image.clone();
    cv::fillPoly(layer, std::vector<std::vector<cv::Point>>{band}, kColours[k % 10], cv::LINE_AA, shift);
    cv::addWeighted(layer, 0.25, image, 0.75, 0, image);
  }
  for (size_t k = 0; k < groups.size(); ++k) {
    std::vector<cv::Point> line;
    for (size_t i = 0; i < groups[k].mean.x.size(); ++i)
      line.push_back(fixed(px(groups[k].mean.x[i], groups[k].mean.y[i])));
    cv::polylines(image, line, false, kColours[k % 10], 2, cv::LINE_AA, shift);
  }
  cv::rectangle(image, area, kBlack, 1);

  // Labels: title, x below, y turned a quarter.
  centred(options.title.empty() ? options.y + " over " + options.x : options.title, {options.width / 2, top / 2}, 0.6);
  centred(options.x, {area.x + area.width / 2, options.height - 22}, 0.55);
  int base = 0;
  const cv::Size ysize = cv::getTextSize(options.y, kFont, 0.55, 1, &base);
  cv::Mat ylabel(ysize.height + base + 4, ysize.width + 4, CV_8UC3, kWhite);
  cv::putText(ylabel, options.y, {2, ysize.height + 2}, kFont, 0.55, kBlack, 1, cv::LINE_AA);
  cv::rotate(ylabel, ylabel, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int ly = std::max(0, area.y + area.height / 2 - ylabel.rows / 2);
  if (ylabel.rows <= options.height - ly) ylabel.copyTo(image(cv::Rect(8, ly, ylabel.cols, ylabel.rows)));

  // Legend, inside the axes in the corner the curves leave emptiest (top left
  // first): a learning curve rises to the top right, a performance profile
  // starts at the top left.
  int widest = 0;
  std::vector<std::string> entries;
  for (const Group& g : groups) {
    entries.push_back(options.count_runs
                          ? g.label + " (" + std::to_string(g.runs.size()) + (g.runs.size() == 1 ? " run)" : " runs)")
                          : g.label);
    widest = std::max(widest, cv::getTextSize(entries.back(), kFont, 0.45, 1, &base).width);
  }
  const cv::Size legend_size(widest + 50, 22 * static_cast<int>(groups.size()) + 8);
  const auto colour = [](const cv::Scalar& c) { return cv::Vec3b(c[0], c[1], c[2]); };
  const cv::Vec3b paper = colour(kWhite), grid = colour(kGridLine);
  cv::Rect legend;
  int least_ink = std::numeric_limits<int>::max();
  for (const cv::Point corner : {cv::Point(0, 0), cv::Point(1, 0), cv::Point(1, 1), cv::Point(0, 1)}) {
    const cv::Rect r(corner.x ? area.x + area.width - 10 - legend_size.width : area.x + 10,
                     corner.y ? area.y + area.height - 10 - legend_size.height : area.y + 10, legend_size.width,
                     legend_size.height);
    const cv::Rect inside = r & cv::Rect(0, 0, image.cols, image.rows);  // labels wider than the axes
    int ink = 0;
    for (int y = inside.y; y < inside.y + inside.height; ++y) {
      for (int x = inside.x; x < inside.x + inside.width; ++x) {
        const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
        ink += c != paper && c != grid;
      }
    }
    if (ink < least_ink) {
      least_ink = ink;
      legend = r;
    }
  }
  cv::rectangle(image, legend, kWhite, cv::FILLED);
  cv::rectangle(image, legend, kGrey, 1);
  for (size_t k = 0; k < groups.size(); ++k) {
    const int y = legend.y + 15 + 22 * static_cast<int>(k);
    cv::line(image, {legend.x + 8, y}, {legend.x + 34, y}, kColours[k % 10], 2, cv::LINE_AA);
    cv::putText(image, entries[k], {legend.x + 40, y + 5}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }
  write_png(options.out, image, "plot");

  nlohmann::json summary = nlohmann::json::array();
  for (const Group& g : groups)
    summary.push_back({{"label", g.label}, {"runs", g.runs.size()}, {"points", g.mean.x.size()}});
  return {{"out", options.out},  {"legend", {legend.x, legend.y, legend.width, legend.height}},
          {"groups", summary},   {"area", {area.x, area.y, area.width, area.height}},
          {"x_range", {x0, x1}}, {"y_range", {y0, y1}}};
}

}  // namespace chore
