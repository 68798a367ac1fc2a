"""The Python package against Gymnasium's contract and chore's C++ Env."""

import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import pytest

import chore

ACTIVITY = "collect_trash"


def low_level_actions(t, rows=None):
    """The actions tests/env_replay.cpp takes: ((7t + 3j) mod 21 - 10) / 10."""
    a = np.array([((7 * t + 3 * j) % 21 - 10) / 10 for j in range(14)], dtype=np.float32)
    return a if rows is None else np.tile(a, (rows, 1))


def episode_bytes(env, seed, steps):
    obs, _ = env.reset(seed=seed)
    chunks = [b"".join(np.ascontiguousarray(v).tobytes() for v in obs.values())]
    for t in range(steps):
        obs, reward, _, _, _ = env.step(low_level_actions(t))
        chunks.append(b"".join(np.ascontiguousarray(v).tobytes() for v in obs.values()))
        chunks.append(np.float64(reward).tobytes())
    return b"".join(chunks)


def test_spaces_hold_what_reset_and_step_return():
    with chore.make(ACTIVITY, observations=["rgb", "depth", "proprio", "is_grasping"]) as env:
        obs, info = env.reset(seed=0)
        assert env.observation_space.contains(obs)
        assert set(obs) == {"rgb", "depth", "proprio", "is_grasping"}
        assert obs["rgb"].shape == (128, 128, 3) and obs["rgb"].dtype == np.uint8
        assert info["elapsed_step"] == 0 and info["total"] > 0
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs)
        assert isinstance(reward, float) and not terminated and not truncated
        assert info["elapsed_step"] == 1
    with chore.make(ACTIVITY, num_envs=3, action_space="primitives", observations=["rgb", "action_mask"],
                    mode="symbolic") as envs:
        obs, info = envs.reset(seed=5)
        assert envs.observation_space.contains(obs)
        assert list(info["episode_seed"]) == [5, 6, 7]
        assert envs.single_action_space.n == len(envs.primitive_actions) > 0
        obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        assert envs.observation_space.contains(obs)
        assert rewards.shape == (3,) and terminated.dtype == np.bool_ and list(info["env_id"]) == [0, 1, 2]
        assert info["_success"].all() and info["_env_id"].dtype == np.bool_  # Gymnasium's masks
        assert type(envs.action_space).__name__ == "MultiDiscrete" and list(envs.action_space.nvec) == [envs.single_action_space.n] * 3


def test_a_seed_fixes_an_episode_bit_for_bit_as_the_cpp_env_plays_it():
    observations = ["rgb", "depth", "proprio"]
    with chore.make(ACTIVITY, observations=observations) as env:
        first = episode_bytes(env, 7, 5)
        assert episode_bytes(env, 7, 5) == first
        assert episode_bytes(env, 8, 5) != first
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "replay.bin")
        subprocess.run([os.environ["CHORE_ENV_REPLAY"], ACTIVITY, "7", "5", out] + observations, check=True)
        with open(out, "rb") as f:
            assert f.read() == first, "the C++ Env played the same episode"
    # A vector env's env i is the env seeded seed + i, whatever the thread count.
    rows = []
    for threads in (1, 2):
        with chore.make(ACTIVITY, num_envs=2, num_threads=threads, observations=observations, seed=6) as envs:
            obs, _ = envs.reset()
            for t in range(5):
                obs, _, _, _, _ = envs.step(low_level_actions(t, 2))
            rows.append(np.array(obs["rgb"][1]))
    assert np.array_equal(rows[0], rows[1])


def test_autoreset_next_step_and_same_step():
    with chore.make(ACTIVITY, num_envs=2, observations=["proprio"], max_episode_steps=2) as envs:
        assert str(envs.metadata["autoreset_mode"]).lower().endswith("next_step")  # Gymnasium's enum or its name
        envs.reset(seed=0)
        for _ in range(2):
            _, _, _, truncated, info = envs.step(low_level_actions(0, 2))
        assert truncated.all() and list(info["elapsed_step"]) == [2, 2]
        obs, rewards, terminated, truncated, info = envs.step(low_level_actions(1, 2))
        assert list(info["elapsed_step"]) == [0, 0], "NEXT_STEP: this step reset them"
        assert not truncated.any() and not rewards.any()
    with chore.make(ACTIVITY, num_envs=2, observations=["proprio"], max_episode_steps=2,
                    autoreset_mode="same_step") as envs:
        assert str(envs.metadata["autoreset_mode"]).lower().endswith("same_step")
        envs.reset(seed=0)
        _, _, _, truncated, info = envs.step(low_level_actions(0, 2))
        assert not info["_final_obs"].any()
        obs, _, _, truncated, info = envs.step(low_level_actions(1, 2))
        assert truncated.all() and info["_final_obs"].all()
        assert list(info["elapsed_step"]) == [0, 0], "SAME_STEP: the new episode's first observation"
        assert list(info["final_info"]["elapsed_step"]) == [2, 2]
        assert not np.array_equal(info["final_obs"]["proprio"], obs["proprio"])


def test_batch_rendering_draws_the_envs_as_per_thread_rendering_does():
    """rendering="batch": every env drawn in one pass (env i in tile i); the
    states are those of per-thread rendering, and env 0 (tile 0 in both) is
    drawn bit for bit alike; the other envs' frames may differ by a rounding
    level on a few edge pixels (CameraView::tile)."""
    frames = {}
    for rendering in ("per_thread", "batch"):
        with chore.make(ACTIVITY, num_envs=3, num_threads=2, observations=["rgb", "proprio"], rendering=rendering,
                        width=64, height=64) as envs:
            envs.reset(seed=1)
            obs, *_ = envs.step(low_level_actions(0, 3))
            frames[rendering] = obs
    assert np.array_equal(frames["batch"]["proprio"], frames["per_thread"]["proprio"])
    assert np.array_equal(frames["batch"]["rgb"][0], frames["per_thread"]["rgb"][0])
    same = np.mean(frames["batch"]["rgb"] == frames["per_thread"]["rgb"])
    assert same > 0.99, same
    assert len(np.unique(frames["batch"]["rgb"])) > 20, "drawn, not one colour"
    with pytest.raises(chore.Error, match="rendering 'gpu': expected per_thread or batch"):
        chore.make(ACTIVITY, num_envs=2, rendering="gpu")
    with pytest.raises(chore.Error, match="rendering needs num_envs"):
        chore.make(ACTIVITY, rendering="batch")


def test_send_recv_returns_batch_size_envs_with_their_ids():
    with chore.make(ACTIVITY, num_envs=4, num_threads=2, batch_size=2, observations=["proprio"]) as envs:
        envs.reset(seed=0)
        envs.send(low_level_actions(0, 4), np.arange(4))
        seen = []
        for _ in range(2):
            obs, rewards, _, _, info = envs.recv()
            assert obs["proprio"].shape[0] == 2 and rewards.shape == (2,)
            seen += list(info["env_id"])
        assert sorted(seen) == [0, 1, 2, 3]
        envs.send(low_level_actions(1, 2), [3, 1])
        _, _, _, _, info = envs.recv()
        assert sorted(info["env_id"]) == [1, 3]
        with pytest.raises(chore.Error, match="recv"):
            envs.recv()  # nothing in flight


@pytest.mark.parametrize("bad, message", [
    (np.full((2, 14), np.nan, np.float32), "NaN"),
    (np.zeros((2, 13), np.float32), "shape"),
    (np.zeros((3, 14), np.float32), "shape"),
    (np.array([["a"] * 14] * 2), "dtype"),
])
def test_bad_actions_raise_chore_error_and_leave_the_env_usable(bad, message):
    with chore.make(ACTIVITY, num_envs=2, observations=["proprio"]) as envs:
        envs.reset(seed=0)
        with pytest.raises(chore.Error, match=message):
            envs.step(bad)
        _, _, _, _, info = envs.step(low_level_actions(0, 2))
        assert list(info["elapsed_step"]) == [1, 1]
    with chore.make(ACTIVITY, observations=["proprio"]) as env:
        env.reset(seed=0)
        with pytest.raises(chore.Error):
            env.step(np.full(14, np.nan, np.float32))
        with pytest.raises(chore.Error, match="14 values"):
            env.step(np.zeros(3, np.float32))
        assert env.step(low_level_actions(0))[4]["elapsed_step"] == 1


def test_a_task_is_an_activity_or_a_scene():
    with chore.make("apartment", observations=["proprio"]) as env:  # a scene: no activity, reward 0
        _, info = env.reset(seed=0)
        assert info["total"] == 0
        assert env.step(low_level_actions(0))[1] == 0.0
    with chore.make("Rs_int", observations=["proprio"]) as env:  # a BEHAVIOR-1K scene's analog
        assert env.reset(seed=0)[1]["total"] == 0
    with pytest.raises(chore.Error, match="neither an activity nor a scene"):
        chore.make("kitchen_of_nowhere")


def test_the_baselines_protocol_options_reach_the_env():
    """A fixed instance is the same at every reset; the policy-failure rule is off by default."""
    with chore.make(ACTIVITY, observations=["proprio"], instances="fixed") as env:
        first = np.array(env.reset(seed=3)[0]["proprio"])
        assert np.array_equal(np.array(env.reset(seed=4)[0]["proprio"]), first)
    with chore.make(ACTIVITY, observations=["proprio"]) as env:
        assert not np.array_equal(np.array(env.reset(seed=4)[0]["proprio"]), first)
    with chore.make(ACTIVITY, action_space="primitives", mode="symbolic", observations=["is_grasping"],
                    max_episode_steps=5) as env:
        env.reset(seed=0)
        place = next(i for i, a in enumerate(env.primitive_actions) if a.startswith("place("))
        for _ in range(5):  # placing with an empty hand: invalid, again and again
            _, _, terminated, truncated, info = env.step(np.array([place]))
            assert not terminated and not info["policy_failure"]
        assert truncated
    with pytest.raises(chore.Error, match="unknown instances 'cached'"):
        chore.make(ACTIVITY, instances="cached")
    with pytest.raises(chore.Error, match="unknown policy_failure_rule 'strict'"):
        chore.make(ACTIVITY, action_space="primitives", policy_failure_rule="strict")


def test_bad_configs_raise_chore_error_with_chores_message():
    with pytest.raises(chore.Error, match="unknown option"):
        chore.make(ACTIVITY, colour="red")
    with pytest.raises(chore.Error, match="unknown activity 'no_such_activity'"):
        chore.make("no_such_activity")
    with pytest.raises(chore.Error, match="width"):
        chore.make(ACTIVITY, width=-1)
    with pytest.raises(chore.Error, match="max_episode_steps"):
        chore.make(ACTIVITY, max_episode_steps=10**30)
    with pytest.raises(chore.Error, match="a list of names"):
        chore.make(ACTIVITY, observations="rgb")
    with pytest.raises(chore.Error, match="num_threads"):
        chore.make(ACTIVITY, num_envs=2, num_threads=3)
    with pytest.raises(chore.Error, match="seed"):
        chore.make(ACTIVITY, num_envs=1, seed=-1)


def test_copy_false_views_chores_buffers_and_steps_write_in_place():
    with chore.make(ACTIVITY, observations=["rgb", "proprio"], copy=False) as env:
        obs, _ = env.reset(seed=0)
        rgb = obs["rgb"]
        assert not rgb.flags.owndata and not rgb.flags.writeable
        before = rgb.copy()
        obs, _, _, _, _ = env.step(low_level_actions(0))
        assert obs["rgb"].__array_interface__["data"][0] == rgb.__array_interface__["data"][0]
        assert not np.array_equal(rgb, before), "the step wrote into the array we hold"
    with chore.make(ACTIVITY, num_envs=2, observations=["proprio"], copy=False) as envs:
        envs.reset(seed=0)
        held = envs.step(low_level_actions(0, 2))[0]["proprio"]
        addresses = {held.__array_interface__["data"][0]}
        for t in range(1, 6):
            latest = envs.step(low_level_actions(t, 2))[0]["proprio"]
            addresses.add(latest.__array_interface__["data"][0])
            if latest.__array_interface__["data"][0] == held.__array_interface__["data"][0]:
                assert np.array_equal(held, latest), "a later step rewrote the buffer we hold"
        assert len(addresses) < 6, "results cycle through chore's own buffers"
    with chore.make(ACTIVITY, observations=["proprio"]) as env:  # copy=True, the default
        obs, _ = env.reset(seed=0)
        kept = obs["proprio"]
        assert kept.flags.owndata
        env.step(low_level_actions(0))
        assert np.array_equal(kept, env.reset(seed=0)[0]["proprio"])


def test_the_gil_is_released_while_envs_step():
    # A thread steps primitives (tens of ms each) while this one keeps time:
    # with the GIL held through a step, this loop would stand still for all of
    # it, so its long pauses would add up to the time spent stepping.
    with chore.make("store_decoration", num_envs=2, num_threads=1, action_space="primitives",
                    observations=["proprio"]) as envs:
        envs.reset(seed=0)
        stop = threading.Event()
        stepping = []

        def step_loop():
            while not stop.is_set():
                t = time.perf_counter()
                envs.step(np.zeros(2, np.int64))
                stepping.append(time.perf_counter() - t)

        worker = threading.Thread(target=step_loop)
        worker.start()
        paused, last = 0.0, time.perf_counter()
        deadline = last + 2.0
        while time.perf_counter() < deadline:
            now = time.perf_counter()
            if now - last > 0.02:  # Python switches threads every 5 ms
                paused += now - last
            last = now
        stop.set()
        worker.join()
    assert len(stepping) >= 3, "the worker stepped"
    assert paused < 0.5 * sum(stepping), (paused, sum(stepping))


def test_ctrl_c_interrupts_a_step_loop_cleanly():
    script = (
        "import chore, numpy as np, sys\n"
        f"envs = chore.make('{ACTIVITY}', num_envs=2, observations=['proprio'])\n"
        "envs.reset(seed=0)\n"
        "print('stepping', flush=True)\n"
        "try:\n"
        "    while True:\n"
        "        envs.step(np.zeros((2, 14), np.float32))\n"
        "except KeyboardInterrupt:\n"
        "    envs.close()\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n")
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "stepping"
    time.sleep(0.3)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=30)
    assert p.returncode == 3, err
    assert "interrupted" in out


def run_script(script, timeout=180):
    """A child interpreter: a crash inside MuJoCo or a hang takes it, not pytest."""
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def test_an_env_serves_any_thread_in_turn_and_one_at_a_time():
    code, out, err = run_script(
        "import chore, numpy as np, threading\n"
        "env = chore.make('collect_trash', action_space='primitives', mode='symbolic',\n"
        "                 observations=['rgb', 'is_grasping'])\n"
        "env.reset(seed=0)\n"
        # In turn from other threads: each renders its frame on its own thread (EGL).
        "for _ in range(3):\n"
        "    t = threading.Thread(target=lambda: env.step(np.array([0])))\n"
        "    t.start(); t.join()\n"
        "errors, steps = [], []\n"
        "def loop():\n"
        "    for _ in range(60):\n"
        "        try:\n"
        "            env.step(np.array([0])); steps.append(1)\n"
        "        except chore.Error as e:\n"
        "            errors.append(str(e))\n"
        "threads = [threading.Thread(target=loop) for _ in range(3)]\n"
        "[t.start() for t in threads]; [t.join() for t in threads]\n"
        "assert all('in use by another thread' in e for e in errors), errors[:3]\n"
        "print('ok', len(steps), len(errors), flush=True)\n")
    assert code == 0, err
    ok, steps, errors = out.split()
    assert ok == "ok" and int(steps) + int(errors) == 180 and int(steps) > 0


def test_envs_made_before_a_fork_raise_in_the_child_and_work_in_the_parent():
    code, out, err = run_script(
        "import chore, numpy as np, os, sys\n"
        "envs = chore.make('collect_trash', num_envs=2, num_threads=2, observations=['proprio'])\n"
        "env = chore.make('collect_trash', observations=['rgb'])\n"
        "envs.reset(seed=0); env.reset(seed=0)\n"
        "pid = os.fork()\n"
        "if pid == 0:\n"
        "    said = []\n"
        "    for e, a in ((envs, np.zeros((2, 14), np.float32)), (env, np.zeros(14, np.float32))):\n"
        "        try:\n"
        "            e.step(a); said.append('stepped')\n"
        "        except chore.Error as error:\n"
        "            said.append('error' if 'before a fork' in str(error) else str(error))\n"
        "    envs.close(); env.close()\n"
        "    del envs, env\n"
        "    print('child', *said, flush=True)\n"
        "    sys.exit(0)\n"
        "_, status = os.waitpid(pid, 0)\n"
        "print('parent', os.waitstatus_to_exitcode(status), flush=True)\n"
        "envs.step(np.zeros((2, 14), np.float32)); env.step(np.zeros(14, np.float32))\n"
        "envs.close(); env.close()\n"
        "print('parent stepped', flush=True)\n")
    assert code == 0, err
    assert out.splitlines() == ["child error error", "parent 0", "parent stepped"], (out, err)
