// Compiled models kept on disk by their MJCF: MuJoCo's binary form (MJB) in a
// folder, under a hash of the document and MuJoCo's version, with a checksum
// of its bytes. The largest scene analog compiles in about a second and loads
// from here in about an eighth of that (docs/activities.md). A file that is not what
// its name says (cut short, altered, another MuJoCo) is compiled afresh and
// replaced; a folder that cannot be written leaves models uncached. The
// folder keeps the kModelCacheFiles most recently used of its own files
// (HASH.mjb starting with its magic; other files are not the cache's).
//
// Trust: the checksum finds damage, not intent. A file altered on purpose with
// its checksum recomputed reaches MuJoCo's loader, which checks the model's
// sizes and references (mj_loadModel refuses what would index out of bounds)
// but not what chore's scene expects of it; the folder is trusted as the
// user's own files are (as ccache's or Python's __pycache__), so keep it where
// only you write, or give `--cache ''`.
#pragma once

#include <functional>
#include <string>

struct mjModel_;

namespace chore {

inline constexpr int kModelCacheFiles = 32;

// load_mjcf (world/mujoco_errors.hpp) through the cache in `dir` ("": none);
// `from_cache` (optional) says whether it was loaded rather than compiled.
// `prepare` (optional) finishes a freshly compiled model before it is cached:
// the cache keeps what it made (a change to what callers prepare bumps the
// file format, model_cache.cpp).
mjModel_* load_mjcf_cached(const std::string& xml, const std::string& what, const std::string& dir,
                           bool* from_cache = nullptr, const std::function<void(mjModel_*)>& prepare = {});

// $CHORE_CACHE, else $XDG_CACHE_HOME/chore, else $HOME/.cache/chore, with
// "/models" after it; "" when none of them is set.
std::string default_model_cache_dir();

}  // namespace chore
