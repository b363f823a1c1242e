#!/usr/bin/env python3
"""Ontogeny against MuJoCo on the same creature: evaluations per second, in one run.

    pip install mujoco                      # not needed by the project, never run in CI
    cargo build --release
    python3 benches/mujoco_compare.py       # the 10-part bench chain and the quadruped
    python3 benches/mujoco_compare.py examples/snake.lsys --evaluations 8

For every creature (an .lsys grown to its last frame, or a creature.json):

1. `ontogeny grow` writes creature.json (its brain), and `ontogeny export` writes the MJCF
   model from that creature.json with the default simulator settings;
2. MuJoCo runs the creature once for the evaluation time with its brain, ported here in numpy
   (linear, sigmoid and oscillator neurons; touch and angle sensors), stepping the control
   every `ontogeny_control_step` (1/60 s) and the physics `ontogeny_substeps` times per control
   step, as Ontogeny does. The actuator commands of that run are recorded;
3. MuJoCo is timed on N evaluations that replay the recorded commands (physics plus a few
   array writes per control step: the controller costs MuJoCo nothing), and on N evaluations
   that run the numpy brain (closer to what a Python user of MuJoCo pays);
4. `ontogeny bench --creature creature.json` times N evaluations in Ontogeny (world built,
   then the evaluation time with the controller on, brain in Rust);
5. it prints evaluations per second for each and the ratio Ontogeny / MuJoCo (replay).

An evaluation is the same in both: from the dropped pose, the evaluation time (20 s) of
controller-on stepping. MuJoCo's model is compiled once and `mj_resetData` starts each
evaluation; Ontogeny builds its world for each one.
"""

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

try:
    import mujoco
except ImportError:
    sys.exit("this script needs MuJoCo: pip install mujoco")

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_CREATURES = ["benches/chain10.lsys", "examples/quadruped.lsys"]


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed:\n{done.stderr}")
    return done.stdout


def custom(model, name):
    """A `<custom><numeric>` or `<text>` the exporter wrote."""
    for i in range(model.nnumeric):
        if mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_NUMERIC, i) == name:
            start, size = model.numeric_adr[i], model.numeric_size[i]
            return model.numeric_data[start : start + size].copy()
    for i in range(model.ntext):
        if mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_TEXT, i) == name:
            start, size = model.text_adr[i], model.text_size[i]
            return bytes(model.text_data[start : start + size - 1]).decode()
    return None


class Brain:
    """Ontogeny's BrainRuntime for the neurons the turtle builds: every neuron updated at once
    from the previous outputs, outputs clipped to [-1, 1]."""

    def __init__(self, creature, model):
        neurons = creature["brain"]["neurons"]
        n = len(neurons)
        self.weights = np.zeros((n, n))
        for link in creature["brain"]["links"]:
            self.weights[link["to"], link["from"]] += link["weight"]
        functions = [neuron["function"] for neuron in neurons]
        unknown = set(functions) - {"linear", "sigmoid", "oscillator"}
        if unknown:
            sys.exit(f"this script's brain has no {', '.join(sorted(unknown))} neurons")
        self.linear = np.array([f == "linear" for f in functions])
        self.sigmoid = np.array([f == "sigmoid" for f in functions])
        self.oscillator = np.array([f == "oscillator" for f in functions])
        self.sensor = np.zeros(n, dtype=bool)
        self.touch = []  # (neuron, geom id)
        self.angle = []  # (neuron, qpos address, lo, hi)
        for i, neuron in enumerate(neurons):
            role = neuron["role"]
            if role["kind"] != "sensor":
                continue
            self.sensor[i] = True
            sensor = role["sensor"]
            if sensor["type"] == "touch":
                geom = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, f"part{sensor['part']}")
                self.touch.append((i, geom))
            elif sensor["type"] == "angle":
                name = f"joint{sensor['joint']}_dof{sensor['dof']}"
                joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
                lo, hi = creature["joints"][sensor["joint"]]["limits"][sensor["dof"]]
                self.angle.append((i, model.jnt_qposadr[joint], lo, hi))
            else:
                sys.exit(f"this script's brain has no {sensor['type']} sensor")
        self.reset()

    def reset(self):
        self.outputs = np.zeros(len(self.sensor))
        self.phases = np.zeros(len(self.sensor))

    def read_sensors(self, data):
        if self.touch:
            ncon = data.ncon
            geoms = data.contact.geom[:ncon]
            close = data.contact.dist[:ncon] <= 1e-3
            touching = set(geoms[close].ravel().tolist())
            for neuron, geom in self.touch:
                self.outputs[neuron] = 1.0 if geom in touching else -1.0
        for neuron, address, lo, hi in self.angle:
            a = data.qpos[address]
            self.outputs[neuron] = np.clip(2.0 * (a - lo) / (hi - lo) - 1.0, -1.0, 1.0)

    def step(self, dt):
        total = self.weights @ self.outputs
        new = self.outputs.copy()
        new[self.linear] = total[self.linear]
        new[self.sigmoid] = np.tanh(total[self.sigmoid])
        frequency = math.pi * (1.0 + np.clip(total[self.oscillator], -1.0, 1.0))
        self.phases[self.oscillator] += frequency * dt
        new[self.oscillator] = np.sin(self.phases[self.oscillator])
        new[self.sensor] = self.outputs[self.sensor]
        self.outputs = np.clip(new, -1.0, 1.0)


class Mujoco:
    """The exported creature in MuJoCo, driven as Ontogeny drives it."""

    def __init__(self, xml, creature):
        self.model = mujoco.MjModel.from_xml_path(str(xml))
        self.data = mujoco.MjData(self.model)
        self.dt = float(custom(self.model, "ontogeny_control_step")[0])
        self.substeps = int(custom(self.model, "ontogeny_substeps")[0])
        self.max_speed = float(custom(self.model, "ontogeny_max_speed")[0])
        self.actuator_model = custom(self.model, "ontogeny_actuator_model")
        neurons = custom(self.model, "ontogeny_actuator_neurons")
        self.neurons = [] if neurons is None else neurons.astype(int)
        torques = custom(self.model, "ontogeny_max_torque")
        self.torques = np.zeros(0) if torques is None else torques
        self.limits = self.model.jnt_range[self.model.actuator_trnid[:, 0]].copy()
        self.brain = Brain(creature, self.model)

    def commands(self, s):
        """ctrl and force range for brain signals s, per actuator (World::drive)."""
        if self.actuator_model == "muscle":
            sign = np.where(s >= 0.0, 1.0, -1.0)  # Rust's signum: +1 for 0
            return self.max_speed * sign, np.abs(s) * self.torques
        if self.actuator_model == "velocity":
            return self.max_speed * s, self.torques
        lo, hi = self.limits[:, 0], self.limits[:, 1]
        return lo + (s + 1.0) / 2.0 * (hi - lo), self.torques

    def evaluate(self, steps, record=None):
        m, d, brain = self.model, self.data, self.brain
        mujoco.mj_resetData(m, d)
        brain.reset()
        for _ in range(steps):
            brain.read_sensors(d)
            brain.step(self.dt)
            ctrl, force = self.commands(brain.outputs[self.neurons])
            d.ctrl[:] = ctrl
            m.actuator_forcerange[:, 0] = -force
            m.actuator_forcerange[:, 1] = force
            if record is not None:
                record.append((ctrl, force))
            mujoco.mj_step(m, d, nstep=self.substeps)

    def replay(self, ctrls, forces):
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        low, high = m.actuator_forcerange[:, 0], m.actuator_forcerange[:, 1]
        for k in range(len(ctrls)):
            d.ctrl[:] = ctrls[k]
            low[:] = -forces[k]
            high[:] = forces[k]
            mujoco.mj_step(m, d, nstep=self.substeps)


def rate(n, function):
    started = time.perf_counter()
    for _ in range(n):
        function()
    return n / (time.perf_counter() - started)


def compare(path, args, workdir):
    name = Path(path).stem
    if path.endswith(".json"):
        creature_json = Path(path)
    else:
        grown = workdir / name
        run([args.ontogeny, "grow", path, "--out", grown])
        creature_json = grown / "creature.json"
    xml = workdir / f"{name}.xml"
    run([args.ontogeny, "export", creature_json, "--format", "mjcf", "--out", xml])
    creature = json.loads(creature_json.read_text())
    sim = Mujoco(xml, creature)
    steps = round(args.seconds / sim.dt)

    record = []
    start = sim.data.qpos[:3].copy()
    sim.evaluate(steps, record)
    moved = np.linalg.norm(sim.data.qpos[:2] - start[:2])
    ctrls = np.array([c for c, _ in record])
    forces = np.array([f for _, f in record])

    out = run([args.ontogeny, "bench", "--creature", creature_json,
               "--evaluations", str(args.evaluations), "--seconds", str(args.seconds)])
    found = re.search(r"one core: ([0-9.]+) evaluations/s \(([0-9.]+) µs per step\)", out)
    if not found:
        sys.exit(f"cannot read ontogeny bench's output:\n{out}")
    ontogeny_rate, ontogeny_step = float(found.group(1)), float(found.group(2))

    sim.replay(ctrls[: steps // 20], forces[: steps // 20])  # warm up
    replay_rate = rate(args.evaluations, lambda: sim.replay(ctrls, forces))
    brain_rate = rate(args.evaluations, lambda: sim.evaluate(steps))

    print(f"{path}: {len(creature['parts'])} parts, {sim.model.nu} actuators, "
          f"{args.seconds:g} s at {sim.dt:.6g} s ({sim.substeps} substeps), "
          f"{args.evaluations} evaluations, one core")
    print(f"  MuJoCo {mujoco.__version__}, commands replayed: {replay_rate:8.2f} evaluations/s "
          f"({1e6 / replay_rate / steps:.1f} µs per control step)")
    print(f"  MuJoCo {mujoco.__version__}, brain in numpy:    {brain_rate:8.2f} evaluations/s")
    print(f"  Ontogeny:                         {ontogeny_rate:8.2f} evaluations/s "
          f"({ontogeny_step:.1f} µs per control step)")
    print(f"  ratio Ontogeny / MuJoCo (replayed): {ontogeny_rate / replay_rate:.2f}")
    print(f"  (in MuJoCo the root part moved {moved:.2f} m)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("creatures", nargs="*", default=DEFAULT_CREATURES,
                        help="L-systems or creature.json files (default: %(default)s)")
    parser.add_argument("--ontogeny", default=str(ROOT / "target/release/ontogeny"),
                        help="the ontogeny binary (default: %(default)s)")
    parser.add_argument("--evaluations", type=int, default=8)
    parser.add_argument("--seconds", type=float, default=20.0,
                        help="simulated seconds per evaluation (default: %(default)s)")
    args = parser.parse_args()
    if not Path(args.ontogeny).exists():
        sys.exit(f"{args.ontogeny} not found: run cargo build --release first")
    with tempfile.TemporaryDirectory() as workdir:
        for path in args.creatures:
            compare(path, args, Path(workdir))


if __name__ == "__main__":
    main()
