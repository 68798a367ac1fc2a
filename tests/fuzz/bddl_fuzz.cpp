// libFuzzer target: BDDL text -> parse (with the shipped vocabulary, and with
// the grammar alone, which lets more reach grounding) -> ground the goal.
// Bad input must end in chore::Error; anything else is a finding: a crash, a
// sanitizer report, another exception, an input slower than -timeout or
// heavier than -rss_limit_mb (scripts/fuzz).
#include <cstdint>
#include <string>
#include <string_view>

#include "base/error.hpp"
#include "tasks/goal.hpp"
#include "tasks/vocabulary.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const chore::Vocabulary vocabulary = chore::load_vocabulary();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const chore::Vocabulary* v : {&vocabulary, static_cast<const chore::Vocabulary*>(nullptr)}) {
    try {
      const chore::Problem problem = chore::parse_bddl(text, "fuzz", {.vocabulary = v});
      chore::ground_goal(problem);
    } catch (const chore::Error&) {
    }
  }
  return 0;
}
