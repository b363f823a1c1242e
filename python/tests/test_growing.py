"""A grammar that grows during the walk, from Python: ``evaluate(PATH, config=...)`` with
``develop = "during"`` equals ``ontogeny eval PATH --config``, and its trajectory has a row
for every part that ever existed, NaN before the part appeared."""

import json

import numpy as np
import pytest

import ontogeny

EXAMPLE = "examples/grow-while-walking.lsys"

CONFIG = """\
[task]
task = "walker"
develop = "during"

[task.walker]
seconds = 2
"""


@pytest.fixture
def config(write_config):
    return write_config("growing.toml", CONFIG)


def test_a_growing_walk_equals_the_command_lines_and_its_trajectory_gains_parts(root, cli, config):
    ours = ontogeny.evaluate(root / EXAMPLE, config=config, record=True)
    theirs = cli.json("eval", EXAMPLE, "--config", config, "--json")
    assert ours.fitness == theirs["fitness"]
    assert json.loads(ours.to_json()) == theirs
    assert ours.terms["grown_parts"] == 12.0
    trajectory = ours.trajectory
    # Three segments dropped, four legs of a shoulder, a hip and a lower leg grown: fifteen
    # parts, by id.
    assert trajectory.shape == (len(ours.times), 15, 3)
    assert not np.isnan(trajectory[:, :3]).any()
    # Each leg part has NaN rows until it appears, and positions from then on.
    for part in range(3, 15):
        present = ~np.isnan(trajectory[:, part, 0])
        assert not present[0]
        assert present[-1]
        first = int(np.argmax(present))
        assert present[first:].all()
        assert np.isnan(trajectory[:first, part]).all()


def test_a_growing_walk_takes_a_grammar_s_path_not_a_creature(root, config):
    creature = ontogeny.load(root / EXAMPLE)
    with pytest.raises(ValueError, match=r'develop = "during": a grammar grows during the walk'):
        ontogeny.evaluate(creature, config=config)


HABITATS = "examples/grow-while-walking-habitats.toml"
CUE = "examples/grow-where-rich.lsys"


def test_a_walk_growing_in_habitats_and_trials_equals_the_command_lines(root, cli):
    ours = ontogeny.evaluate(root / CUE, config=root / HABITATS)
    theirs = cli.json("eval", CUE, "--config", HABITATS, "--json")
    assert ours.fitness == theirs["fitness"]
    assert json.loads(ours.to_json()) == theirs
    # Legs grow where chemical 0 starts at 1, none where it starts at 0.
    grown = [(w["name"], w["terms"]["grown_parts"]) for w in ours.habitats]
    assert grown == [("poor", 0.0), ("poor", 0.0), ("rich", 2.0), ("rich", 2.0)]
    # One habitat alone: its walks, as in the whole evaluation; recorded, growing.
    rich = ontogeny.evaluate(root / CUE, config=root / HABITATS, habitat="rich", record=True)
    assert rich.habitats == ours.habitats[2:]
    assert rich.trajectory.shape[1] == 4
    with pytest.raises(ValueError, match=r"no habitat 'wet'; the habitats are poor, rich"):
        ontogeny.evaluate(root / CUE, config=root / HABITATS, habitat="wet")
