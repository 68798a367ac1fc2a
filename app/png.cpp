#include "app/png.hpp"

#include <opencv2/imgcodecs.hpp>

#include "base/error.hpp"

namespace chore {

void write_png(const std::string& path, const cv::Mat& image, const std::string& what) {
  if (!path.ends_with(".png")) throw Error(what + ": --out '" + path + "' must end in .png");
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw Error(what + ": cannot write '" + path + "': " + e.err);
  }
  if (!written) throw Error(what + ": cannot write '" + path + "'");
}

}  // namespace chore
