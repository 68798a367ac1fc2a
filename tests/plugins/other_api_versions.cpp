// Plugins built against other versions of the policy API: the loader refuses
// them before their factory runs. CHORE_TEST_API_VERSION is the version this
// one claims; without it, it exports none (a plugin from before versions).
#include "policies/policy.hpp"

#ifdef CHORE_TEST_API_VERSION
extern "C" int chore_policy_api_version() {
  return CHORE_TEST_API_VERSION;
}
#endif
extern "C" chore::Policy* chore_create_policy(const chore::PolicySpec*, char*, int) {
  return nullptr;
}
extern "C" void chore_destroy_policy(chore::Policy*) {}
