// `chore activity check` and `chore activity sample`: BDDL files validated and
// grounded; an activity instantiated from a seed and pictured.
#pragma once

#include <opencv2/core.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "env/env.hpp"
#include "tasks/activity_check.hpp"
#include "tasks/bddl.hpp"
#include "tasks/goal.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {

// check_activity for each file; prints objects, goal options and literals to
// `out`, or the file's error (with file:line:col) to `err`. Returns how many
// files failed.
int check_activities(const std::vector<std::string>& files, std::ostream& out, std::ostream& err);

// The robot's head camera (`obs` of an env with "rgb" at head_size) beside a
// top-down view of the whole scene, drawn now (BGR, for OpenCV).
cv::Mat instance_picture(Env& env, const ArrayDict& obs, int head_size, int top_size);

// Instantiates `activity` with `seed` and writes a PNG: the robot's head
// camera beside a top-down view of the scene.
void sample_activity(const std::string& activity, const std::string& scene, uint64_t seed, const std::string& png,
                     std::ostream& out);
// Instantiates `activity` with every seed in [first, last]; prints how many
// succeeded and the time each took. Throws chore::Error at the first failure.
void sample_activity_seeds(const std::string& activity, const std::string& scene, uint64_t first, uint64_t last,
                           std::ostream& out);

}  // namespace chore
