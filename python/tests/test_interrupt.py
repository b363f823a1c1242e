"""Ctrl-C during a long call: each raises ``KeyboardInterrupt`` soon after the signal, the
interpreter goes on working, and an interrupted evolution resumes to the uninterrupted
run's result."""

import os
import signal
import threading
import time

import pytest

import ontogeny

# A derivation that never ends on its own: one module whose parameter grows at every step
# (so the string never stops changing), each step trying 200 guards first (so every step
# costs a few microseconds, whatever a budget of modules times steps allows).
ENDLESS = (
    "axiom: A(0)\n"
    + "".join(f"A(x) : x < -{i} --> A(x + {i})\n" for i in range(1, 201))
    + "A(x) --> A(x + 1)\n"
)
STEPS = 10**9
LONGEST_WALK = 3600  # seconds: the longest a task may last

# How long after the signal the call must have raised: far above the 50 ms between checks,
# loose enough for a loaded machine.
RESPONSE_BOUND = 5.0


def interrupt(call, *, when=lambda: time.sleep(0.3)):
    """Runs ``call`` while a timer thread waits for ``when()`` to return, then sends this
    process SIGINT (Ctrl-C); asserts that ``call`` raised ``KeyboardInterrupt``, and returns
    the seconds from the signal to the exception."""
    # Python's own Ctrl-C handler, as an interactive session has it: a process started in the
    # background by a non-interactive shell (as CI may be) inherits SIGINT ignored, and
    # Python then leaves it ignored.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    sent = []
    done = threading.Event()

    def send():
        when()
        if not done.is_set():
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Thread(target=send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        raised = time.monotonic()
    finally:
        done.set()
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert sent, "the call ended before the signal was sent"
    return raised - sent[0]


@pytest.fixture(scope="module")
def chain(root):
    return ontogeny.load(root / "benches/chain10.lsys")


def test_ctrl_c_stops_grow_with_keyboard_interrupt():
    assert interrupt(lambda: ontogeny.grow(ENDLESS, steps=STEPS)) < RESPONSE_BOUND
    # The interpreter, and the package, go on as before.
    assert ontogeny.grow(ENDLESS, steps=3).parts == 0


def test_ctrl_c_stops_derive_with_keyboard_interrupt():
    assert interrupt(lambda: ontogeny.derive(ENDLESS, steps=STEPS)) < RESPONSE_BOUND
    assert ontogeny.derive(ENDLESS, steps=2)[-1][1] == "A(2)"


def test_ctrl_c_stops_evaluate_with_keyboard_interrupt(chain):
    assert interrupt(lambda: ontogeny.evaluate(chain, seconds=LONGEST_WALK)) < RESPONSE_BOUND
    assert ontogeny.evaluate(chain, seconds=1).status == "ok"


def test_ctrl_c_stops_evaluate_many_with_keyboard_interrupt(chain):
    call = lambda: ontogeny.evaluate_many([chain] * 4, seconds=LONGEST_WALK, threads=2)
    assert interrupt(call) < RESPONSE_BOUND


def test_ctrl_c_stops_evolve_and_resume_ends_as_the_uninterrupted_run(tmp_path):
    settings = dict(encoding="direct", pop=6, gens=5, seconds=10, seed=3, threads=1)
    whole = ontogeny.evolve(out=tmp_path / "whole", **settings)

    cut = tmp_path / "cut"

    def first_generation_stored():
        while True:
            try:
                if ontogeny.Run(cut).generations():
                    return
            except (OSError, ValueError):
                pass  # the run's store is not there yet
            time.sleep(0.02)

    call = lambda: ontogeny.evolve(out=cut, **settings)
    assert interrupt(call, when=first_generation_stored) < RESPONSE_BOUND
    # It kept the generations it had stored, and no more than the run's five.
    kept = len(ontogeny.Run(cut).generations())
    assert 1 <= kept < 5

    resumed = ontogeny.resume(cut, threads=2)
    assert resumed.path == cut
    assert resumed.individuals() == whole.individuals()
    timings = ("wall_seconds", "evaluations_per_second")
    untimed = lambda run: [
        {k: v for k, v in g.items() if k not in timings} for g in run.generations()
    ]
    assert untimed(resumed) == untimed(whole)
    assert len(untimed(whole)) == 5


def test_resume_extends_a_finished_run_and_refuses_a_folder_without_one(tmp_path):
    run = ontogeny.evolve(out=tmp_path / "r", encoding="direct", pop=4, gens=1, seconds=1, seed=2)
    longer = ontogeny.evolve(out=tmp_path / "longer", encoding="direct", pop=4, gens=2, seconds=1, seed=2)
    assert ontogeny.resume(run.path).generations() == run.generations()
    extended = ontogeny.resume(run.path, gens=2)
    assert extended.individuals() == longer.individuals()
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="holds no run"):
        ontogeny.resume(tmp_path / "empty")
    with pytest.raises(FileNotFoundError):
        ontogeny.resume(tmp_path / "missing")
