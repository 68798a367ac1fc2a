// The report of `chore reproduce`: from the table's finished runs, the rows of
// Table A.13 (mean and std over training seeds beside the paper's numbers,
// which are data: assets/paper/table_a13.json), the failure breakdown, the
// wall-clock per run, the machine and the commit, the learning curves
// (OUT/curves/ACTIVITY.png), and the same as Markdown.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "app/reproduce.hpp"

namespace chore {

// One (activity, method, training seed) of the table: its run folder, and
// whether it is done (its cell.json matches the options).
struct TableCell {
  std::string activity, method;
  uint64_t seed = 0;
  std::filesystem::path dir;
  bool done = false;
  std::string label() const { return activity + " " + method + " seed " + std::to_string(seed); }
};

// baselines.json's content but "videos", "failures", the invocation's
// wall-clock and protocol.policy_failure, which the runner adds; draws the
// curves of the done cells.
nlohmann::json baselines_report(const std::vector<TableCell>& cells, const ReproduceOptions& options,
                                std::ostream& log);
// baselines.md from baselines.json's content.
std::string baselines_markdown(const nlohmann::json& report, const ReproduceOptions& options);

// The paper's Table A.13 (success score Q, mean and std over training seeds);
// NaN for a cell the paper has not.
struct PaperQ {
  double mean, std;
};
PaperQ paper_q(const std::string& method, const std::string& activity);
// The paper's names: "RL-Prim.Hist.", "CleanTable" (the name itself if unknown).
std::string method_title(const std::string& method);
std::string activity_title(const std::string& activity);

// "12.5 min", "2.35 h".
std::string format_hours(double seconds);
// A done run's OUT/runs/.../cell.json, every field the report reads checked
// (a damaged file is a chore::Error naming it and the field).
nlohmann::json read_cell_summary(const std::filesystem::path& path);
// The last row's value of `column` in a metrics.csv, or `fallback`.
double last_metric(const std::filesystem::path& path, const std::string& column, double fallback);

}  // namespace chore
