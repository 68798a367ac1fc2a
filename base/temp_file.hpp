// Files written whole or not at all: each is written beside its final path
// under a temporary name of the writing process's own, FINAL.tmp.PID.N, then
// renamed over FINAL, so that a reader never sees half a file and two writers
// never share a temporary. A writer killed mid-write (kill -9, a power cut)
// leaves its temporary behind; the next start removes those of processes that
// no longer run, and never a file of any other name.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace chore {

// FINAL.tmp.PID.N for this process, N counting this process's temporaries.
std::filesystem::path temp_path_for(const std::filesystem::path& final_path);

// The FINAL of `file_name` when it is a temporary of the form above whose
// writer no longer runs; "" when it is not one (any other name, or a writer
// that still runs).
std::string dead_writers_final_name(const std::string& file_name);

// Removes the files in `dir` (not below) that are temporaries of writers that
// no longer run and whose FINAL `is_ours` accepts, and such folders with what
// is in them (a scratch folder named by temp_path_for; never through a
// symbolic link). Errors are ignored: what cannot be removed now is left for
// the next start.
void remove_dead_writers_temps(const std::filesystem::path& dir,
                               const std::function<bool(const std::string& final_name)>& is_ours);

}  // namespace chore
