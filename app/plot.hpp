// `chore plot` (scripts/plot): learning curves from trainers' metrics.csv files
// to a PNG, drawn with OpenCV (no plotting dependency).
//
//   chore plot --out curves.png --y success_rate runs/ppo_seed0/metrics.csv runs/ppo_seed1/metrics.csv ...
//
// A metrics.csv has a header row (env_steps,wall_s,episodes,success_rate,
// mean_q,mean_return,mean_length, then any others) and one row per report.
// Runs are grouped by label: "LABEL=path/metrics.csv" names it; otherwise it is
// the run directory's name less a seed suffix ("ppo_seed2" -> "ppo"). Each
// group is drawn as its mean over runs (linearly interpolated at 200 x values
// across the range all its runs cover) with a band of +- one (population)
// standard deviation, kept within the runs' lowest and highest values there;
// a single run is drawn as logged.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace chore {

struct PlotOptions {
  std::vector<std::string> runs;  // [LABEL=]metrics.csv
  std::string out;                // .png
  std::string x = "env_steps", y = "success_rate";
  std::string title;  // empty: "<y> over <x>"
  int width = 960, height = 600;
  bool count_runs = true;  // the legend says how many runs each group has
};

// Draws the PNG. Returns the groups (label, runs, points), the plot frame
// (the pixel rectangle of the axes and the data ranges they span) and the
// legend's pixel rectangle (x, y, width, height).
// chore::Error naming the file (and line) for a missing file or column or a
// value that is not a number.
nlohmann::json plot_curves(const PlotOptions& options);

}  // namespace chore
