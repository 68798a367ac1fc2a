// The vocabulary BDDL files are checked against (tasks/bddl.hpp's
// Vocabulary): the dialects' domains and BEHAVIOR's room types, shipped in
// tasks/domains, and the synsets of the knowledge base.
#pragma once

#include <memory>
#include <string>

#include "tasks/bddl.hpp"
#include "tasks/knowledge_base.hpp"

namespace chore {

// Reads <dir>/igibson.bddl, <dir>/omnigibson.bddl and <dir>/room_types.txt;
// synsets are checked against `kb`.
Vocabulary load_vocabulary(std::shared_ptr<const KnowledgeBase> kb,
                           const std::string& dir = default_tasks_dir() + "/domains");

}  // namespace chore
