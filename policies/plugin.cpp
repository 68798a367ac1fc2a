#include "policies/plugin.hpp"

#include <dlfcn.h>

#include <filesystem>

#include "base/error.hpp"

namespace chore {
namespace {

// The loaded library, closed when the last policy made by it is gone.
using Library = std::shared_ptr<void>;

// Forwards to the plugin's policy; destroys it with the plugin's own deleter
// (it was allocated by the plugin's allocator and code) before the library closes.
class PluginPolicy : public Policy {
 public:
  PluginPolicy(Library library, Policy* policy, chore_destroy_policy_fn destroy)
      : library_(std::move(library)), policy_(policy), destroy_(destroy) {}
  ~PluginPolicy() override { destroy_(policy_); }
  void act(const Batch& batch, std::span<float> actions) override { policy_->act(batch, actions); }
  void reset(std::span<const int> env_ids) override { policy_->reset(env_ids); }

 private:
  Library library_;  // declared first: released last
  Policy* policy_;
  chore_destroy_policy_fn destroy_;
};

}  // namespace

std::unique_ptr<Policy> load_policy_plugin(const std::string& library, const PolicySpec& spec) {
  const std::string where = "policy plugin '" + library + "'";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(library, ec)) throw Error(where + ": no such file");
  // RTLD_NOW: a symbol the plugin needs and this process lacks fails here,
  // with a message, rather than at its first call.
  void* handle = dlopen(std::filesystem::absolute(library).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw Error(where + ": cannot load it: " + (why ? why : "unknown reason"));
  }
  const Library lib(handle, [](void* h) { dlclose(h); });
  auto create = reinterpret_cast<chore_create_policy_fn>(dlsym(handle, "chore_create_policy"));
  auto destroy = reinterpret_cast<chore_destroy_policy_fn>(dlsym(handle, "chore_destroy_policy"));
  if (!create || !destroy) {
    throw Error(where + ": it does not export " + (!create ? "chore_create_policy" : "chore_destroy_policy") +
                " (define them with CHORE_POLICY_PLUGIN(YourPolicy), policies/policy.hpp)");
  }
  // Its types must be laid out as this process's: the same API version. Plugins
  // from before versions existed (API 1) export no version.
  auto version = reinterpret_cast<chore_policy_api_version_fn>(dlsym(handle, "chore_policy_api_version"));
  const int built_for = version ? version() : 1;
  if (built_for != CHORE_POLICY_API_VERSION) {
    throw Error(where + ": built against chore's policy API version " + std::to_string(built_for) +
                ", this chore has version " + std::to_string(CHORE_POLICY_API_VERSION) +
                ": rebuild it against this chore's headers");
  }
  char error[1024] = "";
  Policy* policy = create(&spec, error, sizeof error);
  if (!policy) {
    throw Error(where + ": the factory refused: " + (error[0] ? error : "(no reason given)"));
  }
  return std::make_unique<PluginPolicy>(lib, policy, destroy);
}

}  // namespace chore
