// Lookup in the registries (lists of entries with a `name`: observation
// modalities, reward kinds, baselines), with the error a bad name gets.
#pragma once

#include <string>
#include <vector>

#include "base/error.hpp"

namespace chore {

// The entry named `name`; chore::Error "unknown WHAT 'NAME' (known: a, b, c)".
template <class Entry>
const Entry& find_by_name(const std::vector<Entry>& list, const std::string& name, const std::string& what) {
  std::string known;
  for (const Entry& e : list) {
    if (e.name == name) return e;
    known += (known.empty() ? "" : ", ") + e.name;
  }
  throw Error("unknown " + what + " '" + name + "' (known: " + known + ")");
}

}  // namespace chore
