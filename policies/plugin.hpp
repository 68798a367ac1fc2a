// Custom policies from shared libraries (the CHORE_POLICY_PLUGIN entry points
// of policies/policy.hpp):
//
//   std::unique_ptr<chore::Policy> p = chore::load_policy_plugin("libmine.so", spec);
//
// The library stays loaded while the policy lives; destroying the policy calls
// the plugin's chore_destroy_policy, then closes the library.
//
// Symbols: a plugin links no chore library. Its calls into chore (Space and
// ArrayDict members, ...) resolve at load time against the process that loads
// it, which must export them: the `chore` executable is linked with
// ENABLE_EXPORTS (-rdynamic) for this. So one copy of chore's code and state
// serves the host and its plugins, whichever chore build the plugin was
// compiled against, as long as the headers match.
#pragma once

#include <memory>
#include <string>

#include "policies/policy.hpp"

namespace chore {

// chore::Error naming the library when the file is missing, is not a shared
// library (or needs symbols this process lacks), lacks an entry point, or
// when its factory refuses `spec` (with the factory's message).
std::unique_ptr<Policy> load_policy_plugin(const std::string& library, const PolicySpec& spec);

}  // namespace chore
