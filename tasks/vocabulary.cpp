#include "tasks/vocabulary.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <mutex>
#include <sstream>
#include <utility>

#include "base/json_file.hpp"

namespace chore {

std::shared_ptr<const KnowledgeBase> dialect_knowledge_base(Domain domain) {
  static std::mutex mutex;
  static std::map<Domain, std::shared_ptr<const KnowledgeBase>> loaded;
  const std::lock_guard lock(mutex);
  std::shared_ptr<const KnowledgeBase>& kb = loaded[domain];
  if (!kb) {
    kb =
        KnowledgeBase::load(default_tasks_dir() + (domain == Domain::igibson ? "/kb/behavior-100" : "/kb/behavior-1k"));
  }
  return kb;
}

Vocabulary load_vocabulary(std::shared_ptr<const KnowledgeBase> kb, const std::string& dir) {
  const auto read = [&](const std::string& name) {
    const std::string path = dir + "/" + name;
    return std::pair{path, read_text_file(path, 1u << 20, "a vocabulary file")};
  };
  Vocabulary v;
  const auto [igibson, igibson_text] = read("igibson.bddl");
  v.igibson = parse_domain(igibson_text, igibson);
  const auto [omnigibson, omnigibson_text] = read("omnigibson.bddl");
  v.omnigibson = parse_domain(omnigibson_text, omnigibson);
  std::istringstream rooms(read("room_types.txt").second);
  for (std::string line; std::getline(rooms, line);) {
    line.erase(std::remove_if(line.begin(), line.end(), [](char c) { return std::isspace(uint8_t(c)); }), line.end());
    if (!line.empty() && !line.starts_with('#')) v.room_types.insert(line);
  }
  v.unknown_synset = [kb = std::move(kb)](Domain domain, const std::string& synset) {
    return (kb ? kb : dialect_knowledge_base(domain))->unknown(synset);
  };
  return v;
}

}  // namespace chore
