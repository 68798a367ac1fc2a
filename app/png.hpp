// Writing the PNG pictures of the commands (observe, plot, activity sample).
#pragma once

#include <opencv2/core.hpp>

#include <string>

namespace chore {

// Writes `image` (BGR) to `path`, which must end in .png; a bad path or a
// failed write is a chore::Error naming `what` (the command) and the path,
// never OpenCV's exception.
void write_png(const std::string& path, const cv::Mat& image, const std::string& what);

}  // namespace chore
