// The `chore` executable: runs the command app/command_line.hpp read (bench,
// activity check/sample, expert, eval, video, observe, plot, train,
// reproduce). Bad arguments and bad input files exit with status 2 and a
// message naming what is wrong.
#include <malloc.h>

#include <filesystem>
#include <iostream>
#include <string>

#include "app/activity_commands.hpp"
#include "app/activity_coverage.hpp"
#include "app/command_line.hpp"
#include "base/error.hpp"
#include "base/json_file.hpp"
#include "policies/evaluate.hpp"
#include "training/checkpoint.hpp"

namespace {

std::vector<chore::PolicySource> sources_of(const chore::PolicyArgs& a, const std::string& command) {
  if (!a.checkpoints.empty()) {
    // Each checkpoint brings its env; --activity, --mode and --max-steps override it.
    chore::set_policy_threads(1);
    std::vector<chore::PolicySource> sources;
    for (const std::string& path : a.checkpoints) {
      auto loaded = std::make_shared<chore::LoadedPolicy>(chore::load_policy(path, a.sample));
      chore::EnvConfig env = loaded->env;
      if (!a.activity.empty()) env.activity = a.activity;
      if (!a.mode.empty()) env.primitive_mode = chore::parse_execution_mode(a.mode);
      if (a.max_steps > 0) env.max_episode_steps = a.max_steps;
      sources.push_back({path, env, [loaded, path](const chore::VectorEnv&) {
                           if (!loaded->policy) throw chore::Error(path + ": its policy is already in use");
                           return std::move(loaded->policy);
                         }});
    }
    return sources;
  }
  if (a.activity.empty()) throw chore::Error(command + ": --activity is required");
  const chore::ExecutionMode mode = chore::parse_execution_mode(a.mode.empty() ? "physical" : a.mode);
  const bool primitives = a.expert || a.action_space == "primitives";
  const int max_steps = a.max_steps > 0 ? a.max_steps : primitives ? 60 : 500;
  if (a.expert) return {chore::expert_source(a.activity, mode, max_steps)};
  if (a.plugin.empty())
    throw chore::Error(command + ": give the policy: --checkpoint PATH, --policy-plugin LIB.so or --expert");
  chore::EnvConfig env;
  env.activity = a.activity;
  env.action_space = a.action_space;
  env.primitive_mode = mode;
  env.max_episode_steps = max_steps;
  if (!a.observations.empty()) {
    env.observations = a.observations;
  } else if (primitives) {
    env.observations.push_back("action_mask");
  }
  return {chore::plugin_source(a.plugin, a.plugin_options, env)};
}

std::vector<chore::PolicySource> policy_sources(const chore::PolicyArgs& a, const std::string& command) {
  std::vector<chore::PolicySource> sources = sources_of(a, command);
  // --instances overrides every env's, a checkpoint's own included.
  if (!a.instances.empty()) {
    for (chore::PolicySource& s : sources) s.env.instances = a.instances;
  }
  return sources;
}

// A stream's text, a line at a time, as valid UTF-8 (base/utf8.hpp): file
// names, BDDL tokens and paths reach the output as the user wrote them.
class ValidUtf8Lines : public std::streambuf {
 public:
  explicit ValidUtf8Lines(std::ostream& stream) : stream_(stream), target_(stream.rdbuf(this)) {}
  ~ValidUtf8Lines() override {
    sync();
    stream_.rdbuf(target_);
  }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_ += traits_type::to_char_type(c);
    return c == '\n' && sync() != 0 ? traits_type::eof() : c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) {
      if (traits_type::eq_int_type(overflow(traits_type::to_int_type(s[i])), traits_type::eof())) return i;
    }
    return n;
  }
  int sync() override {
    const std::string text = chore::valid_utf8(line_);
    line_.clear();
    if (target_->sputn(text.data(), static_cast<std::streamsize>(text.size())) !=
        static_cast<std::streamsize>(text.size())) {
      return -1;
    }
    return target_->pubsync();
  }

 private:
  std::ostream& stream_;
  std::streambuf* target_;
  std::string line_;
};

}  // namespace

int main(int argc, char** argv) {
  const ValidUtf8Lines out(std::cout), err(std::cerr);
  // glibc hands large freed blocks (image batches, tensors) back to the kernel
  // and maps them again at the next use; each new page is a fault, and faults
  // are dear on a VM: a StoreDecoration PPO minibatch update took 143-160 ms,
  // 33-40 ms with the memory kept (docs/benchmarks.md#training). Keep it.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
  const chore::ParsedCommandLine parsed = chore::parse_command_line(argc, argv, std::cout, std::cerr);
  if (!parsed.command) return parsed.exit_status;
  const chore::CommandLine& c = *parsed.command;
  try {
    switch (c.command) {
      case chore::Command::activity_check:
        if (const int failed = chore::check_activities(c.check_files, std::cout, std::cerr)) {
          std::cerr << "chore: error: " << failed << " of " << c.check_files.size() << " files failed" << std::endl;
          return 2;
        }
        break;
      case chore::Command::activity_sample:
        if (c.sample.seeds) {
          chore::sample_activity_seeds(c.sample.name, c.sample.scene, c.sample.seeds->first, c.sample.seeds->second,
                                       std::cout);
        } else {
          chore::sample_activity(c.sample.name, c.sample.scene, c.sample.seed, c.sample.out, std::cout);
        }
        break;
      case chore::Command::activity_coverage: {
        const nlohmann::json results = chore::activity_coverage(c.coverage, std::cerr);
        std::cout << (c.json ? chore::json_text(results, 2) + "\n" : chore::format_coverage(results));
        break;
      }
      case chore::Command::activity_solve: {
        const nlohmann::json results = chore::activity_coverage(c.coverage, std::cerr);
        std::cout << (c.json ? chore::json_text(results, 2) + "\n" : chore::format_solve(results));
        break;
      }
      case chore::Command::scene_list:
        chore::list_scenes(std::cout);
        break;
      case chore::Command::scene_build: {
        const nlohmann::json result = chore::build_scene(c.scene_build);
        std::cout << (c.json ? chore::json_text(result, 2) + "\n" : chore::format_scene_build(result));
        break;
      }
      case chore::Command::expert: {
        const nlohmann::json results = chore::run_expert(c.expert, std::cerr);
        std::cout << (c.json ? chore::json_text(results, 2) + "\n" : chore::format_expert(results));
        break;
      }
      case chore::Command::eval: {
        nlohmann::json results = nlohmann::json::array();
        for (const chore::PolicySource& source : policy_sources(c.policy, "eval")) {
          results.push_back(chore::evaluate(source, c.eval, std::cerr));
          if (!c.json) std::cout << chore::format_evaluation(results.back());
        }
        if (c.json) std::cout << chore::json_text(results, 2) << std::endl;
        break;
      }
      case chore::Command::video: {
        const std::vector<chore::PolicySource> sources = policy_sources(c.policy, "video");
        const nlohmann::json r = chore::record_video(sources.front(), c.video, std::cerr);
        std::cout << "video: " << r["out"].get<std::string>() << ", " << r["frames"] << " frames of " << r["width"]
                  << "x" << r["height"] << " at " << r["fps"] << " fps (" << r["codec"].get<std::string>() << "); "
                  << r["steps"] << " steps, " << (r["success"].get<bool>() ? "success" : "no success") << ", Q "
                  << r["q"] << "\n";
        break;
      }
      case chore::Command::observe: {
        const nlohmann::json r = chore::observe_panel(c.observe);
        std::cout << "observe: " << r["out"].get<std::string>() << " (" << r["scene"].get<std::string>()
                  << "): " << r["instances"] << " instances of " << r["classes"].size() << " classes in view, depth to "
                  << r["max_depth_m"] << " m, flow up to " << r["max_flow_px"] << " px\n";
        break;
      }
      case chore::Command::plot: {
        const nlohmann::json r = chore::plot_curves(c.plot);
        std::cout << "plot: " << c.plot.out << ":";
        for (const auto& g : r["groups"]) {
          std::cout << " " << g["label"].get<std::string>() << " (" << g["runs"]
                    << (g["runs"] == 1 ? " run)" : " runs)");
        }
        std::cout << "\n";
        break;
      }
      case chore::Command::train:
        chore::run_train(c.train, std::cerr);
        break;
      case chore::Command::reproduce: {
        const nlohmann::json r = chore::reproduce(c.reproduce, std::cerr);
        if (!r["failures"].empty()) {
          std::cerr << "chore: " << r["failures"].size() << " run(s) failed; the rest are reported" << std::endl;
          return 1;
        }
        break;
      }
      case chore::Command::bench: {
        const nlohmann::json results = chore::run_bench(c.bench, std::cerr);
        std::cout << (c.json ? chore::json_text(results, 2) + "\n" : chore::format_bench(results));
        break;
      }
    }
  } catch (const chore::Error& e) {
    std::cerr << "chore: error: " << e.what() << std::endl;
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path given on the command line or in a file: bad input, not a fault.
    std::cerr << "chore: error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "chore: internal error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
