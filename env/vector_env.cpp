#include "env/vector_env.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "base/error.hpp"
#include "base/memory.hpp"
#include "env/env_impl.hpp"

namespace chore {
namespace {

// Cameras per render pass on a GPU (one row of tiles).
constexpr int kMaxTiles = 16;

// One batch of results: what recv() returns, written in place by the workers.
struct Block {
  ArrayDict obs, final_obs;
  std::vector<float> rewards;
  std::vector<std::uint8_t> terminated, truncated;
  std::vector<int> env_ids;
  std::vector<Info> infos, final_infos;
  int done = 0;  // rows written; guarded by the pool's mutex
  // Rendering::batch with same_step: rows whose episode ended, their last
  // frame not yet drawn and their env not yet reset; guarded by the mutex.
  std::vector<int> ended;

  Block(const Space& space, int rows, bool with_final)
      : obs(space, rows), rewards(rows), terminated(rows), truncated(rows), env_ids(rows), infos(rows) {
    if (with_final) {
      final_obs = ArrayDict(space, rows);
      final_infos.resize(rows);
    }
  }

  Batch view(bool with_final) const {
    return Batch{&obs, rewards, terminated, truncated, env_ids, infos, with_final ? &final_obs : nullptr, final_infos};
  }
};

struct Task {
  std::vector<int> envs;
  bool reset = false;
};

struct Row {
  Block* block;
  int index;
};

}  // namespace

struct VectorEnv::Impl {
  VectorEnvConfig config;
  int num_envs, batch, action_size;
  bool same_step;
  int tile_count = 1;  // cameras per render pass
  bool batch_rendering = false;
  std::unique_ptr<Renderer> batch_renderer;  // Rendering::batch: the VectorEnv's one context
  std::vector<std::unique_ptr<Env>> envs;
  std::vector<std::vector<float>> actions;     // per env, set by send()
  std::vector<std::optional<uint64_t>> seeds;  // per env, set by reset()
  // in_flight: sent, and its result not yet returned by recv() (a finished
  // step waiting in a block is still in flight: sending it again would step
  // the env before the caller has seen the result).
  std::vector<std::uint8_t> in_flight, needs_reset;
  std::vector<std::unique_ptr<Block>> ring;
  std::unique_ptr<Block> reset_block;
  int64_t claimed = 0;   // rows claimed in the ring so far
  int64_t returned = 0;  // blocks returned by recv()
  int64_t pending = 0;   // rows sent and not yet returned
  bool was_reset = false, closed = false, stopping = false;
  Block* held = nullptr;  // the block the caller is reading

  std::mutex mutex;
  std::condition_variable work_ready, rows_done;
  std::deque<Task> queue;
  std::exception_ptr error;
  std::vector<std::thread> workers;

  explicit Impl(const VectorEnvConfig& c) : config(c) {
    num_envs = c.num_envs;
    if (num_envs <= 0) throw Error("vector env: num_envs must be at least 1, got " + std::to_string(num_envs));
    if (c.num_threads <= 0 || c.num_threads > num_envs) {
      throw Error("vector env: num_threads must be in 1.." + std::to_string(num_envs) +
                  " (one env per thread at most), got " + std::to_string(c.num_threads));
    }
    batch = c.batch_size == 0 ? num_envs : c.batch_size;
    if (batch < 1 || batch > num_envs) {
      throw Error("vector env: batch_size must be in 1.." + std::to_string(num_envs) + ", got " +
                  std::to_string(c.batch_size));
    }
    same_step = c.autoreset == AutoReset::same_step;
    if (c.render_tiles < 0) throw Error("vector env: render_tiles must be >= 0");
    const int wanted = c.render_tiles > 0                              ? c.render_tiles
                       : std::string(Renderer::platform()) == "device" ? kMaxTiles
                                                                       : 1;
    batch_rendering = c.rendering == Rendering::batch;
    tile_count = std::max(1, std::min({batch_rendering ? num_envs : wanted, num_envs,
                                       Renderer::tile_capacity(c.env.width, c.env.height)}));
    const EnvAssets assets = load_assets(c.env);
    envs.push_back(std::make_unique<Env>(c.env, assets));
    // Rows not yet returned span at most ceil(N/B) + 1 blocks; one more is held.
    const int blocks = (num_envs + batch - 1) / batch + 2;
    double row_bytes = 0;
    for (const auto& [name, field] : envs[0]->observation_space().fields) {
      row_bytes += static_cast<double>(field.element_count() * dtype_size(field.dtype));
    }
    check_fits_in_memory(row_bytes * (static_cast<double>(blocks) * batch * (same_step ? 2 : 1) + num_envs),
                         "vector env of " + std::to_string(num_envs) + " envs at " + std::to_string(c.env.width) + "x" +
                             std::to_string(c.env.height) + ": the buffer of its batched observations");
    while (static_cast<int>(envs.size()) < num_envs) envs.push_back(std::make_unique<Env>(c.env, assets));
    action_size = static_cast<int>(envs[0]->action_space().element_count());
    actions.assign(num_envs, std::vector<float>(action_size, 0.f));
    seeds.resize(num_envs);
    in_flight.assign(num_envs, 0);
    needs_reset.assign(num_envs, 0);
    for (int b = 0; b < blocks; ++b) {
      ring.push_back(std::make_unique<Block>(envs[0]->observation_space(), batch, same_step));
    }
    reset_block = std::make_unique<Block>(envs[0]->observation_space(), num_envs, false);
    for (int t = 0; t < c.num_threads; ++t) workers.emplace_back([this] { work(); });
  }

  ~Impl() { stop(); }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (stopping) return;
      stopping = true;
    }
    work_ready.notify_all();
    for (std::thread& t : workers) t.join();
  }

  void work() {
    std::unique_ptr<Renderer> renderer;  // this thread's EGL context
    for (;;) {
      Task task;
      {
        std::unique_lock<std::mutex> lock(mutex);
        work_ready.wait(lock, [&] { return stopping || !queue.empty(); });
        if (queue.empty()) return;
        task = std::move(queue.front());
        queue.pop_front();
      }
      std::vector<Row> rows = claim(task), ended;
      try {
        run(task, rows, renderer, ended);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex);
        for (const Row& row : ended) row.block->ended.push_back(row.index);
        for (size_t i = 0; i < rows.size(); ++i) {
          rows[i].block->done++;
        }
      }
      rows_done.notify_all();
    }
  }

  std::vector<Row> claim(const Task& task) {
    std::vector<Row> rows;
    std::lock_guard<std::mutex> lock(mutex);
    for (int env : task.envs) {
      if (task.reset) {
        rows.push_back({reset_block.get(), env});
        continue;
      }
      Block* block = ring[(claimed / batch) % ring.size()].get();
      // With batch == num_envs every round holds each env once: keep env order.
      const int index = batch == num_envs ? env : static_cast<int>(claimed % batch);
      claimed++;
      rows.push_back({block, index});
    }
    return rows;
  }

  // Env i always draws in tile i % tiles(), whichever worker renders it, so
  // that images do not depend on the thread count (see CameraView::tile).
  int tiles() const { return tile_count; }

  void add_views(std::vector<CameraView>& views, int env, ArrayDict& obs, int index) {
    for (CameraView v : envs[env]->impl().camera_views(obs, index)) {
      v.tile = env % tiles();
      views.push_back(v);
    }
  }

  void render(std::vector<CameraView>& views, std::unique_ptr<Renderer>& renderer) {
    if (views.empty()) return;
    if (!renderer) {
      renderer = std::make_unique<Renderer>(envs[0]->world().model(), config.env.width, config.env.height, tiles());
    }
    renderer->render(views);
    views.clear();
  }

  // Steps (or resets) the task's envs and, rendering per thread, draws them;
  // rendering in batches, the rows whose episode ended with same_step go to
  // `deferred`, not yet reset (render_block() draws and resets them).
  void run(const Task& task, const std::vector<Row>& rows, std::unique_ptr<Renderer>& renderer,
           std::vector<Row>& deferred) {
    std::vector<CameraView> views;
    std::vector<size_t> ended;  // same_step: rows whose episode ended this step
    for (size_t i = 0; i < rows.size(); ++i) {
      const int e = task.envs[i];
      Env& env = *envs[e];
      Block& b = *rows[i].block;
      const int r = rows[i].index;
      b.env_ids[r] = e;
      Env::Impl::Outcome out;
      if (task.reset || needs_reset[e]) {
        out.info = env.impl().reset_state(task.reset ? seeds[e] : std::nullopt);
        needs_reset[e] = 0;
      } else {
        out = env.impl().advance(actions[e]);
        if (out.terminated || out.truncated) {
          if (same_step) {
            ended.push_back(i);
          } else {
            needs_reset[e] = 1;
          }
        }
      }
      out.info.env_id = e;
      b.rewards[r] = static_cast<float>(out.reward);
      b.terminated[r] = out.terminated;
      b.truncated[r] = out.truncated;
      b.infos[r] = out.info;
    }
    if (batch_rendering) {
      for (size_t i : ended) deferred.push_back(rows[i]);
      return;
    }
    // same_step: observe the last state of ended episodes, then reset them.
    for (size_t i : ended) {
      Block& b = *rows[i].block;
      add_views(views, task.envs[i], b.final_obs, rows[i].index);
      b.final_infos[rows[i].index] = b.infos[rows[i].index];
    }
    render(views, renderer);
    for (size_t i : ended) {
      Block& b = *rows[i].block;
      envs[task.envs[i]]->impl().finish_observation(b.final_obs, rows[i].index);
      Info info = envs[task.envs[i]]->impl().reset_state(std::nullopt);
      info.env_id = task.envs[i];
      b.infos[rows[i].index] = info;
    }
    for (size_t i = 0; i < rows.size(); ++i) {
      add_views(views, task.envs[i], rows[i].block->obs, rows[i].index);
    }
    render(views, renderer);
    for (size_t i = 0; i < rows.size(); ++i) {
      envs[task.envs[i]]->impl().finish_observation(rows[i].block->obs, rows[i].index);
    }
  }

  // Rendering::batch, on the caller's thread once the workers have written
  // the block's `rows`: the ended episodes' last frames in one pass, their
  // resets, then every row's frame in one pass. The context is released
  // after, for whichever thread calls next.
  void render_block(Block& b, int rows) {
    std::vector<CameraView> views;
    if (!batch_renderer) {
      batch_renderer =
          std::make_unique<Renderer>(envs[0]->world().model(), config.env.width, config.env.height, tiles());
    }
    const auto draw = [&] {
      if (!views.empty()) batch_renderer->render(views);
      views.clear();
    };
    std::sort(b.ended.begin(), b.ended.end());  // the workers' order varies
    for (int r : b.ended) add_views(views, b.env_ids[r], b.final_obs, r);
    draw();
    for (int r : b.ended) {
      const int e = b.env_ids[r];
      envs[e]->impl().finish_observation(b.final_obs, r);
      b.final_infos[r] = b.infos[r];
      Info info = envs[e]->impl().reset_state(std::nullopt);
      info.env_id = e;
      b.infos[r] = info;
    }
    b.ended.clear();
    for (int r = 0; r < rows; ++r) add_views(views, b.env_ids[r], b.obs, r);
    draw();
    for (int r = 0; r < rows; ++r) envs[b.env_ids[r]]->impl().finish_observation(b.obs, r);
    batch_renderer->release_thread();
  }

  // Splits env ids into tasks of at most one render pass each (one env on
  // llvmpipe): idle workers take the next task, so an env that costs more
  // (a view with more geoms) does not hold up a whole share.
  void dispatch(std::span<const int> ids, bool reset) {
    const size_t per_worker = (ids.size() + config.num_threads - 1) / config.num_threads;
    // (Rendering in batches, a task is an env's physics alone.)
    const size_t share = batch_rendering ? 1 : std::max<size_t>(1, std::min<size_t>(per_worker, tile_count));
    {
      std::lock_guard<std::mutex> lock(mutex);
      for (size_t first = 0; first < ids.size(); first += share) {
        Task task;
        task.reset = reset;
        task.envs.assign(ids.begin() + first, ids.begin() + std::min(ids.size(), first + share));
        queue.push_back(std::move(task));
      }
    }
    work_ready.notify_all();
  }

  void check_open() const {
    if (closed) throw Error("vector env: used after close()");
  }

  void rethrow_error() {
    if (error) {
      std::exception_ptr e = error;
      error = nullptr;
      std::rethrow_exception(e);
    }
  }
};

VectorEnv::VectorEnv(const VectorEnvConfig& config) : impl_(std::make_unique<Impl>(config)) {}
VectorEnv::~VectorEnv() = default;

int VectorEnv::num_envs() const {
  return impl_->num_envs;
}
int VectorEnv::batch_size() const {
  return impl_->batch;
}
const Space& VectorEnv::single_observation_space() const {
  return impl_->envs[0]->observation_space();
}
const EnvState& VectorEnv::state(int i) const {
  if (i < 0 || i >= impl_->num_envs) throw Error("vector env: no env " + std::to_string(i));
  return *impl_->envs[i];
}

const Space& VectorEnv::single_action_space() const {
  return impl_->envs[0]->action_space();
}

Batch VectorEnv::reset(std::optional<uint64_t> seed) {
  std::vector<std::optional<uint64_t>> seeds(impl_->num_envs);
  for (size_t i = 0; i < seeds.size(); ++i) {
    if (seed) seeds[i] = *seed + i;
  }
  return reset(seeds);
}

Batch VectorEnv::reset(std::span<const std::optional<uint64_t>> seeds) {
  Impl& m = *impl_;
  m.check_open();
  if (seeds.size() != static_cast<size_t>(m.num_envs)) {
    throw Error("vector env: reset() with " + std::to_string(seeds.size()) + " seeds for " +
                std::to_string(m.num_envs) + " envs");
  }
  std::vector<int> ids(m.num_envs);
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    if (m.pending > 0) throw Error("vector env: reset() while envs are in flight; recv() them first");
    for (int i = 0; i < m.num_envs; ++i) {
      ids[i] = i;
      m.seeds[i] = seeds[i];
      m.needs_reset[i] = 0;
    }
    m.reset_block->done = 0;
  }
  m.dispatch(ids, true);
  std::unique_lock<std::mutex> lock(m.mutex);
  m.rows_done.wait(lock, [&] { return m.reset_block->done == m.num_envs; });
  m.rethrow_error();
  if (m.batch_rendering) {
    lock.unlock();
    m.render_block(*m.reset_block, m.num_envs);
    lock.lock();
  }
  m.was_reset = true;
  return m.reset_block->view(false);
}

void VectorEnv::send(std::span<const float> actions, std::span<const int> env_ids) {
  Impl& m = *impl_;
  m.check_open();
  if (!m.was_reset) throw Error("vector env: send() before reset()");
  if (actions.size() != env_ids.size() * m.action_size) {
    throw Error("vector env: got " + std::to_string(actions.size()) + " action values for " +
                std::to_string(env_ids.size()) + " envs of action size " + std::to_string(m.action_size));
  }
  for (size_t k = 0; k < actions.size(); ++k) {
    if (!std::isfinite(actions[k])) {
      throw Error("vector env: action value " + std::to_string(actions[k]) + " for env " +
                  std::to_string(env_ids[k / m.action_size]) + " (index " + std::to_string(k % m.action_size) + ")");
    }
  }
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    std::vector<std::uint8_t> seen(m.num_envs, 0);
    for (int e : env_ids) {
      if (e < 0 || e >= m.num_envs) throw Error("vector env: env id " + std::to_string(e) + " out of range");
      if (m.in_flight[e] || seen[e]) throw Error("vector env: env " + std::to_string(e) + " is already in flight");
      seen[e] = 1;
    }
    for (int e : env_ids) m.in_flight[e] = 1;
    for (size_t k = 0; k < env_ids.size(); ++k) {
      std::copy_n(actions.begin() + k * m.action_size, m.action_size, m.actions[env_ids[k]].begin());
    }
    m.pending += static_cast<int64_t>(env_ids.size());
  }
  m.dispatch(env_ids, false);
}

Batch VectorEnv::recv() {
  Impl& m = *impl_;
  m.check_open();
  std::unique_lock<std::mutex> lock(m.mutex);
  if (m.pending < m.batch) {
    throw Error("vector env: recv() would wait forever: " + std::to_string(m.pending) +
                " results pending, batch_size is " + std::to_string(m.batch));
  }
  if (m.held) m.held->done = 0;  // the caller is done with the previous batch
  Block* block = m.ring[m.returned % m.ring.size()].get();
  m.rows_done.wait(lock, [&] { return block->done == m.batch; });
  m.rethrow_error();
  if (m.batch_rendering) {
    // No worker writes this block now (its rows are all in); the others go on.
    lock.unlock();
    m.render_block(*block, m.batch);
    lock.lock();
  }
  m.returned++;
  m.pending -= m.batch;
  for (int e : block->env_ids) m.in_flight[e] = 0;
  m.held = block;
  return block->view(m.same_step);
}

Batch VectorEnv::step(std::span<const float> actions) {
  Impl& m = *impl_;
  if (m.batch != m.num_envs) {
    throw Error("vector env: step() needs batch_size == num_envs; use send()/recv()");
  }
  std::vector<int> ids(m.num_envs);
  for (int i = 0; i < m.num_envs; ++i) ids[i] = i;
  send(actions, ids);
  return recv();
}

void VectorEnv::close() {
  if (impl_->closed) return;
  impl_->stop();
  impl_->closed = true;
}

}  // namespace chore
