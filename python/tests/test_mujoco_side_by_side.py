"""A process that imports chore and MuJoCo's own Python package of another
version: each runs on its own libmujoco (chore's wheel-built 4.x, the other
package's 3.x), whichever is imported first."""

import os
import subprocess
import sys

import pytest

import chore

OTHER_MUJOCO = os.environ.get("CHORE_OTHER_MUJOCO", "")

# A ball dropped from 1 m for 100 steps of MuJoCo's default 2 ms: semi-implicit
# Euler puts it at z = 1 - g dt^2 n (n + 1) / 2.
SCRIPT = r"""
import hashlib, sys
import numpy as np
order = sys.argv[1]
if order == "mujoco-first":
    import mujoco
import chore
if order == "chore-first":
    import mujoco
with chore.make("collect_trash", observations=["rgb", "depth", "proprio"]) as env:
    obs, _ = env.reset(seed=3)
    h = hashlib.sha256()
    for t in range(20):
        obs, reward, *_ = env.step(np.full(env.action_space.shape, 0.05 * (t % 7) - 0.15, dtype=np.float32))
        for v in obs.values():
            h.update(np.ascontiguousarray(v).tobytes())
        h.update(np.float64(reward).tobytes())
print("chore", chore.mujoco_version, h.hexdigest())
if order != "chore-alone":
    m = mujoco.MjModel.from_xml_string(
        "<mujoco><worldbody><body pos='0 0 1'><freejoint/><geom size='0.1'/></body></worldbody></mujoco>")
    d = mujoco.MjData(m)
    for _ in range(100):
        mujoco.mj_step(m, d)
    print("mujoco", mujoco.mj_versionString(), repr(float(d.qpos[2])))
"""


def run(order):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (env.get("PYTHONPATH", ""), OTHER_MUJOCO) if p)
    out = subprocess.run([sys.executable, "-c", SCRIPT, order], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return dict((line.split()[0], line.split()[1:]) for line in out.stdout.splitlines())


def test_chore_and_another_mujocos_python_package_in_one_process():
    assert OTHER_MUJOCO, "CHORE_OTHER_MUJOCO names the folder of another MuJoCo's package (ctest sets it)"
    alone = run("chore-alone")["chore"]
    assert alone[0] == chore.mujoco_version and alone[0].startswith("4.")
    dt, n, g = 0.002, 100, 9.81
    for order in ("mujoco-first", "chore-first"):
        got = run(order)
        assert got["chore"] == alone, order  # the same episode, bit for bit, on chore's own MuJoCo
        assert got["mujoco"][0] == "3.17.0", order
        assert float(got["mujoco"][1]) == pytest.approx(1 - g * dt * dt * n * (n + 1) / 2, abs=1e-9), order
