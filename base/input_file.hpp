// Files a user names, read within bounds. A path to a character device
// (/dev/zero reports size 0 and never ends), a FIFO (opening it blocks until a
// writer comes) or a folder is refused before it is opened, and a read stops
// at its limit whatever the file reports as its size.
#pragma once

#include <cstddef>
#include <string>

namespace chore {

// chore::Error naming `path` and what it is unless it is a regular file (after
// symbolic links): "PATH: not a file (a FIFO); expected WHAT". `what` names
// the kind expected: "a BDDL file".
void check_regular_file(const std::string& path, const std::string& what);

// The file's bytes: check_regular_file, then at most max_bytes read; a file
// that holds more is chore::Error, as is one that cannot be opened or read.
std::string read_text_file(const std::string& path, size_t max_bytes, const std::string& what);

}  // namespace chore
