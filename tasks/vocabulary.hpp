// The vocabulary BDDL files are checked against (tasks/bddl.hpp's
// Vocabulary): the dialects' domains and BEHAVIOR's room types, shipped in
// tasks/domains, and the synsets of the knowledge base.
#pragma once

#include <memory>
#include <string>

#include "tasks/bddl.hpp"
#include "tasks/knowledge_base.hpp"

namespace chore {

// The knowledge base a dialect's files name synsets of: BEHAVIOR-100's
// (tasks/kb/behavior-100) for igibson, BEHAVIOR-1K's (tasks/kb/behavior-1k)
// for omnigibson. Each is loaded once per process; thread-safe.
std::shared_ptr<const KnowledgeBase> dialect_knowledge_base(Domain domain);

// Reads <dir>/igibson.bddl, <dir>/omnigibson.bddl and <dir>/room_types.txt;
// synsets are checked against `kb`, or, without one, against the knowledge
// base of each file's dialect.
Vocabulary load_vocabulary(std::shared_ptr<const KnowledgeBase> kb = nullptr,
                           const std::string& dir = default_tasks_dir() + "/domains");

}  // namespace chore
