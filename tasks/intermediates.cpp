#include "tasks/intermediates.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace chore {

void declare_intermediates(Problem& problem, const KnowledgeBase& kb, const TransitionRules& rules) {
  if (problem.domain != Domain::omnigibson) return;
  std::vector<std::string> made;
  const auto have = [&](const std::string& synset) {
    for (const ObjectDecl& d : problem.objects) {
      if (d.type == synset || (kb.contains(d.type) && kb.contains(synset) && kb.is_a(d.type, synset))) return true;
    }
    return std::find(made.begin(), made.end(), synset) != made.end();
  };
  std::vector<std::string> wanted;
  for (const Literal& l : problem.init) {
    if (l.predicate != "future" || l.negated || l.args.size() != 1) continue;
    const auto d = std::find_if(problem.objects.begin(), problem.objects.end(),
                                [&](const ObjectDecl& o) { return o.name == l.args[0]; });
    if (d != problem.objects.end()) wanted.push_back(d->type);
  }
  for (int depth = 0; depth < kIntermediateDepth && !wanted.empty(); ++depth) {
    std::vector<std::string> next;
    for (const std::string& synset : wanted) {
      for (const TransitionRule* r : rules.producing(synset)) {
        for (const SynsetCount& in : r->inputs) {
          if (have(in.synset) || rules.producing(in.synset).empty()) continue;
          made.push_back(in.synset);
          next.push_back(in.synset);
        }
      }
    }
    wanted = std::move(next);
  }
  for (const std::string& synset : made) {
    const std::string name = synset + kIntermediateSuffix;
    problem.objects.push_back({name, synset});
    problem.init.push_back({"future", {name}});
  }
}

}  // namespace chore
