"""Habitats from Python: ``evaluate(config=..., habitat=...)`` equals ``ontogeny eval --config``
(each habitat's and trial's walk in ``Evaluation.habitats``), a file is grown in each habitat's
chemical array as ``eval FILE --config`` grows it, bad names and clashing keywords raise
``ValueError``, ``Run.individuals()`` and ``Run.habitats()`` give each individual's walks, and
``genome_habitats`` gives what ``ontogeny genome show --habitats --json`` prints."""

import json

import pytest

import ontogeny

CHAIN = "benches/chain10.lsys"

# Half-second walks of the walker, two trials in each habitat: what the configs below share.
WALKER_TRIALS = """\
[task]
task = "walker"

[task.walker]
seconds = 0.5

[task.trials]
count = 2
"""

CONFIG = WALKER_TRIALS + """\
offset = 0.2

[[task.habitats]]
name = "level"

[[task.habitats]]
name = "hill"
[task.habitats.world]
slope = { degrees = 10 }
"""


@pytest.fixture
def config(write_config):
    return write_config("habitats.toml", CONFIG)


def test_evaluate_in_habitats_equals_the_command_lines_eval(root, cli, config):
    creature = ontogeny.load(root / CHAIN)
    ours = ontogeny.evaluate(creature, config=config)
    theirs = cli.json("eval", CHAIN, "--config", config, "--json")
    assert [(w["name"], w["trial"]) for w in ours.habitats] == [
        ("level", 0), ("level", 1), ("hill", 0), ("hill", 1),
    ]
    assert ours.habitats == theirs["habitats"]
    assert ours.fitness == theirs["fitness"]
    assert json.loads(ours.to_json()) == theirs
    hill = ontogeny.evaluate(creature, config=config, habitat="hill")
    theirs = cli.json("eval", CHAIN, "--config", config, "--habitat", "hill", "--json")
    assert hill.habitats == theirs["habitats"] == ours.habitats[2:]
    assert hill.fitness == theirs["fitness"]
    # A recorded evaluation plays the habitat's first trial; the fitness is still the aggregate.
    recorded = ontogeny.evaluate(creature, config=config, habitat="hill", record=True)
    assert recorded.fitness == hill.fitness
    assert recorded.trajectory.shape[1] == 10
    # Without habitats: no walks of its own.
    assert ontogeny.evaluate(creature, seconds=0.5).habitats == []


ARRAYS = WALKER_TRIALS + """\
heading = 15
strength = 10

[[task.habitats]]
name = "poor"
environment = [0.0]

[[task.habitats]]
name = "rich"
environment = [1.0]
"""


def test_evaluate_grows_a_file_in_each_habitats_array_as_the_command_lines_eval(
    root, cli, tmp_path
):
    config = tmp_path / "arrays.toml"
    config.write_text(ARRAYS)
    plastic = root / "examples" / "plastic-lsystem.lsys"
    ours = ontogeny.evaluate(plastic, config=config)
    theirs = cli.json("eval", plastic, "--config", config, "--json")
    assert json.loads(ours.to_json()) == theirs
    # Grown in each habitat's array: 5 parts where chemical 0 is 0, 7 where it is 1.
    assert [(w["name"], w["trial"], w["parts"]) for w in ours.habitats] == [
        ("poor", 0, 5), ("poor", 1, 5), ("rich", 0, 7), ("rich", 1, 7),
    ]
    rich = ontogeny.evaluate(str(plastic), config=config, habitat="rich")
    theirs = cli.json("eval", plastic, "--config", config, "--habitat", "rich", "--json")
    assert rich.habitats == theirs["habitats"] == ours.habitats[2:]
    assert rich.fitness == theirs["fitness"]
    # A creature grown once cannot walk where its body would grow otherwise.
    with pytest.raises(ValueError, match=r"evaluate\(PATH, config=\.\.\.\) grows it"):
        ontogeny.evaluate(ontogeny.load(plastic), config=config)
    with pytest.raises(FileNotFoundError, match="absent.lsys"):
        ontogeny.evaluate(tmp_path / "absent.lsys", config=config)
    with pytest.raises(TypeError, match="evaluate takes a Creature or a file's path, not int"):
        ontogeny.evaluate(3, config=config)


def test_a_bad_habitat_or_a_clashing_keyword_raises_value_error(root, config, tmp_path):
    creature = ontogeny.load(root / CHAIN)
    with pytest.raises(ValueError, match="no habitat 'marsh'; the habitats are level, hill"):
        ontogeny.evaluate(creature, config=config, habitat="marsh")
    with pytest.raises(ValueError, match=r"seconds= cannot be given with it"):
        ontogeny.evaluate(creature, config=config, seconds=2)
    with pytest.raises(ValueError, match=r"habitat='hill' names one of a config's"):
        ontogeny.evaluate(creature, habitat="hill")
    grown = tmp_path / "grown.toml"
    grown.write_text(CONFIG.replace('name = "level"', 'name = "level"\nenvironment = [1]'))
    with pytest.raises(ValueError, match="habitat 'level' sets the chemical array"):
        ontogeny.evaluate(creature, config=grown)
    bad = tmp_path / "bad.toml"
    bad.write_text(CONFIG.replace("degrees = 10", "degrees = 95"))
    with pytest.raises(ValueError, match=r"bad.toml:17:21"):
        ontogeny.evaluate(creature, config=bad)


def test_a_runs_individuals_carry_their_walks_in_each_habitat(tmp_path, config):
    text = 'encoding = "direct"\nseed = 3\n\n[ga]\npopulation = 4\ngenerations = 1\n\n' + config.read_text()
    path = tmp_path / "run.toml"
    path.write_text(text)
    run = ontogeny.evolve(path, out=tmp_path / "run")
    for individual in run.individuals(0):
        walks = individual["habitats"]
        assert [(w["name"], w["trial"]) for w in walks] == [
            ("level", 0), ("level", 1), ("hill", 0), ("hill", 1),
        ]
        if individual["status"] == "ok":
            fitnesses = sorted(w["fitness"] for w in walks)
            assert individual["fitness"] == sum(fitnesses) / 4
    # Run.habitats picks an individual by rank, as replay does: the best first.
    ranked = sorted(run.individuals(0), key=lambda i: -i["fitness"])
    assert run.habitats(0, 1) == ranked[0]["habitats"]
    assert run.habitats() == run.habitats(0, rank=1)
    with pytest.raises(ValueError, match="rank must be 1 to 4, not 5"):
        run.habitats(0, 5)
    with pytest.raises(ValueError, match="generation=3: .* has generations 0 to 0"):
        run.habitats(3)
    plain = ontogeny.evolve(out=tmp_path / "plain", pop=4, gens=1, seconds=0.5, encoding="direct")
    assert "habitats" not in plain.individuals(0)[0]
    assert plain.habitats() == []


def test_genome_habitats_equals_genome_show_habitats(root, cli, tmp_path):
    config = root / "examples" / "habitats.toml"
    plastic = root / "examples" / "plastic-lsystem.lsys"
    ours = ontogeny.genome_habitats(config, plastic)
    assert ours == cli.json("genome", "show", "--habitats", config, plastic, "--json")
    assert [h["name"] for h in ours["habitats"]] == ["poor", "rich"]
    assert [h["creature"]["parts"] for h in ours["habitats"]] == [5, 7]
    assert ours["differences"][0]["parts"] == [5, 7]
    assert ours["depends_on_habitat"] is True
    assert ours["verdict"] == "the body depends on the habitat"
    # A genome that reads nothing grows the same body in both.
    fixed = ontogeny.genome_habitats(str(config), str(root / "examples" / "hornby-walker.lsys"))
    assert fixed["depends_on_habitat"] is False
    assert fixed["differences"][0]["same"] is True
    # A configuration without habitats, or a missing file, is refused.
    plain = tmp_path / "plain.toml"
    plain.write_text('[task]\ntask = "walker"\n')
    with pytest.raises(ValueError, match=r"plain.toml: it has no \[\[task.habitats\]\]"):
        ontogeny.genome_habitats(plain, plastic)
    with pytest.raises(FileNotFoundError, match="absent.lsys"):
        ontogeny.genome_habitats(config, tmp_path / "absent.lsys")
