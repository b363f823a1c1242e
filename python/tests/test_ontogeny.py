"""The Python package against the command line: equal results, equal batches, errors as
exceptions, arrays of the documented shapes."""

import json
import math

import numpy as np
import pytest

import ontogeny

CHAIN = "benches/chain10.lsys"
TWO_BOXES = "axiom: forward(1) revolute forward(1) output(1)\n"


def test_evaluate_equals_the_command_lines_eval_bit_for_bit(root, cli):
    creature = ontogeny.load(root / CHAIN)
    ours = ontogeny.evaluate(creature, "walker", seconds=2)
    theirs = cli.json("eval", CHAIN, "--task", "walker", "--seconds", "2", "--json")
    assert ours.fitness == theirs["fitness"]
    assert ours.status == theirs["status"]
    assert ours.terms == theirs["terms"]
    assert json.loads(ours.to_json()) == theirs


def test_every_task_setting_and_fitness_equals_the_command_line(root, cli):
    creature = ontogeny.load(root / "examples/thrower.lsys")
    cases = [
        (dict(task="jump", seconds=1, setting="fast"), ["--task", "jump", "--seconds", "1", "--setting", "fast"]),
        (dict(task="walker", seconds=1, fitness="distance"), ["--task", "walker", "--seconds", "1", "--fitness", "distance"]),
        (dict(task="walker", seconds=1, fitness="D_w - 0.5 * drag"), ["--task", "walker", "--seconds", "1", "--fitness", "D_w - 0.5 * drag"]),
        (dict(task="jump", seconds=1, fitness="2 * height"), ["--task", "jump", "--seconds", "1", "--fitness", "2 * height"]),
        (dict(task="aim", seconds=2, target=(3, 1, 0)), ["--task", "aim", "--seconds", "2", "--target", "3,1,0"]),
        (dict(task="stand", seconds=1), ["--task", "stand", "--seconds", "1"]),
    ]
    for kwargs, flags in cases:
        ours = ontogeny.evaluate(creature, **kwargs)
        theirs = cli.json("eval", "examples/thrower.lsys", *flags, "--json")
        assert (ours.fitness, ours.status, ours.terms) == (
            theirs["fitness"],
            theirs["status"],
            theirs["terms"],
        ), kwargs


def test_sim_sets_a_knob_as_the_command_lines_flag_does(root, cli):
    creature = ontogeny.load(root / CHAIN)
    default = ontogeny.evaluate(creature, seconds=1)
    cases = [
        (dict(setting="fast", sim={"substeps": 4}), ["--setting", "fast", "--substeps", "4"]),
        (dict(sim={"dt": 0.02, "strength": 5000}), ["--time-step", "0.02", "--strength", "5000"]),
        (dict(sim={"joints": "multibody", "self_collision": False}), ["--joints", "multibody", "--no-self-collision"]),
    ]
    for kwargs, flags in cases:
        ours = ontogeny.evaluate(creature, seconds=1, **kwargs)
        theirs = cli.json("eval", CHAIN, "--seconds", "1", *flags, "--json")
        assert json.loads(ours.to_json()) == theirs, kwargs
        assert ours.fitness != default.fitness, kwargs
        [many] = ontogeny.evaluate_many([creature], seconds=1, **kwargs)
        assert json.loads(many.to_json()) == theirs, kwargs


def test_a_bad_knob_in_sim_raises_value_error_with_the_range_or_the_keys():
    creature = ontogeny.grow(TWO_BOXES)
    keys = (
        "control_step, substeps, solver_iterations, pgs_iterations, rest_substeps, "
        "rest_solver_iterations, joints, self_collision, friction, actuator, strength, "
        "strength_from, muscle_speed, max_speed, drop_height, explosion_distance, speed_limit, "
        "energy_tolerance"
    )
    cases = [
        ({"substeps": 0}, "sim['substeps'] must be 1 to 64, not 0"),
        ({"substeps": -1}, "sim['substeps'] must be 1 to 64, not -1"),
        ({"substeps": 2.5}, "sim['substeps'] must be a whole number, not 2.5"),
        ({"control_step": 1}, "sim['control_step'] must be in [0.001, 0.1] seconds, not 1"),
        ({"friction": -1}, "sim['friction'] must be finite and not negative, not -1"),
        ({"friction": "high"}, "sim['friction'] must be a number, not 'high'"),
        ({"self_collision": 1}, "sim['self_collision'] must be True or False, not 1"),
        ({"joints": "multibodi"}, "sim['joints'] must be one of impulse, multibody, not 'multibodi' (did you mean multibody?)"),
        ({"dt": 0.02, "control_step": 0.02}, "sim gives control_step twice (dt is its older name)"),
        ({"substep": 2}, f"unknown key 'substep' in sim (did you mean substeps?); its keys are {keys}"),
        ({3: 2}, "sim's keys must be strings, not 3"),
    ]
    for sim, message in cases:
        with pytest.raises(ValueError) as error:
            ontogeny.evaluate(creature, seconds=1, sim=sim)
        assert str(error.value) == message, sim
    with pytest.raises(ValueError) as error:
        ontogeny.evaluate_many([creature], seconds=1, sim={"substeps": 65})
    assert str(error.value) == "sim['substeps'] must be 1 to 64, not 65"


def test_the_task_list_is_the_command_lines(cli):
    assert list(ontogeny.TASKS) == ["walker", "jump", "catapult", "aim", "stand", "swim"]
    help_text = cli("eval", "--help")
    for name, summary in ontogeny.TASKS.items():
        assert f"- {name}:" in help_text and summary in help_text, name


def test_a_grown_creature_is_the_command_lines(root, cli):
    text = (root / "examples/quadruped.lsys").read_text()
    creature = ontogeny.grow(text)
    theirs = cli.json("grow", "examples/quadruped.lsys", "--json")
    assert creature.parts == theirs["parts"]
    assert creature.neurons == theirs["neurons"]
    assert creature.joints == sum(theirs["joints"].values())
    assert json.loads(creature.to_json()) == json.loads(ontogeny.load(root / "examples/quadruped.lsys").to_json())


def test_a_creature_json_loads_back_to_the_same_evaluation(tmp_path):
    creature = ontogeny.grow(TWO_BOXES)
    path = tmp_path / "creature.json"
    path.write_text(creature.to_json())
    again = ontogeny.load(path)
    assert ontogeny.evaluate(again, seconds=1).fitness == ontogeny.evaluate(creature, seconds=1).fitness


def test_derive_gives_the_command_lines_frames(root, cli):
    frames = ontogeny.derive((root / "examples/algae.lsys").read_text())
    lines = cli("derive", "examples/algae.lsys").splitlines()
    assert [f"{int(t)}: {modules}" for t, modules, env in frames] == lines


ROW = """\
define PARTS = 2
define LENGTH = PARTS * 0.25
axiom: S(PARTS)
derivation length: 4
S(n) : n > 0 --> forward(LENGTH) S(n - 1)
"""


def test_defines_set_a_grammars_defines_as_the_command_lines_define_does(tmp_path, cli):
    assert ontogeny.grow(ROW).parts == 2
    grown = ontogeny.grow(ROW, defines={"PARTS": 3})
    assert grown.parts == 3
    # LENGTH follows PARTS: three parts 0.75 long.
    assert grown.sizes[:, 0].tolist() == [0.75, 0.75, 0.75]
    path = tmp_path / "row.lsys"
    path.write_text(ROW)
    assert ontogeny.load(path, defines={"PARTS": 4}).parts == 4
    with pytest.warns(UserWarning, match="fixed point at step 2"):
        frames = ontogeny.derive(ROW, defines={"PARTS": 1, "LENGTH": 2})
    assert frames[-1][1] == "forward(2) S(0)"
    assert cli("derive", path, "--last", "--define", "PARTS=1", "--define", "LENGTH=2") == "4: forward(2) S(0)\n"
    with pytest.raises(ValueError, match=r"cannot set PART: the grammar has no define by that name \(did you mean PARTS\?\); its defines are PARTS, LENGTH"):
        ontogeny.grow(ROW, defines={"PART": 3})
    with pytest.raises(ValueError, match=r"defines: the value of PARTS, NaN, is not a finite number"):
        ontogeny.grow(ROW, defines={"PARTS": float("nan")})


def test_grammar_seed_seeds_the_grammar_as_the_command_lines_grammar_seed_does(root, cli):
    text = (root / "examples/stochastic-plant.lsys").read_text()
    last = cli("derive", "examples/stochastic-plant.lsys", "--grammar-seed", "3", "--last")
    frames = ontogeny.derive(text, grammar_seed=3)
    assert f"{int(frames[-1][0])}: {frames[-1][1]}\n" == last
    # Another seed, another plant.
    assert ontogeny.derive(text, grammar_seed=4)[-1][1] != frames[-1][1]
    grown = cli.json("grow", "examples/stochastic-plant.lsys", "--grammar-seed", "3", "--json")
    assert ontogeny.grow(text, grammar_seed=3).parts == grown["parts"]
    assert ontogeny.load(root / "examples/stochastic-plant.lsys", grammar_seed=3).parts == grown["parts"]


SEEDED = """\
seed: 1
define R = uniform(0.1, 0.9)
axiom: A(R)
derivation length: 4
A(x) --> forward(x) A(x) : 0.5
A(x) --> forward(0.3) revolute1 A(x) : 0.5
"""


def test_grammar_seed_is_the_seed_line_edited_defines_included(tmp_path):
    edited = SEEDED.replace("seed: 1", "seed: 7")
    frames = ontogeny.derive(SEEDED, grammar_seed=7)
    assert frames == ontogeny.derive(edited)
    assert frames != ontogeny.derive(SEEDED)
    # The axiom carries R, drawn from the seed when the grammar is read.
    assert frames[0][1] != ontogeny.derive(SEEDED)[0][1]
    grown = ontogeny.grow(SEEDED, grammar_seed=7)
    assert grown.to_json() == ontogeny.grow(edited).to_json()
    path = tmp_path / "seeded.lsys"
    path.write_text(SEEDED)
    assert ontogeny.load(path, grammar_seed=7).to_json() == grown.to_json()


def test_seed_is_the_old_name_of_grammar_seed_and_says_so(root):
    text = (root / "examples/stochastic-plant.lsys").read_text()
    note = (
        r"seed=3 is read as grammar_seed=3, the seed of the grammar's stochastic rules "
        r"\(seed= is the genetic algorithm's seed, in evolve and compare\)"
    )
    with pytest.warns(DeprecationWarning, match=note):
        old = ontogeny.derive(text, seed=3)
    assert old == ontogeny.derive(text, grammar_seed=3)
    with pytest.warns(DeprecationWarning, match=note):
        assert ontogeny.grow(text, seed=3).parts == ontogeny.grow(text, grammar_seed=3).parts
    path = root / "examples/stochastic-plant.lsys"
    with pytest.warns(DeprecationWarning, match=note):
        assert ontogeny.load(path, seed=3).parts == ontogeny.load(path, grammar_seed=3).parts
    both = r"grammar_seed= and seed= are one argument \(seed= is its old name\): give one"
    for call in (ontogeny.derive, ontogeny.grow):
        with pytest.raises(TypeError, match=both):
            call(text, grammar_seed=3, seed=3)
    with pytest.raises(TypeError, match=both):
        ontogeny.load(path, grammar_seed=3, seed=4)


def test_evaluate_many_equals_evaluate_one_by_one_in_order(root):
    creatures = [
        ontogeny.load(root / CHAIN),
        ontogeny.grow(TWO_BOXES),
        ontogeny.load(root / "examples/quadruped.lsys"),
        ontogeny.grow("axiom: forward(0.5)\n"),
    ]
    alone = [ontogeny.evaluate(c, seconds=1) for c in creatures]
    together = ontogeny.evaluate_many(creatures, seconds=1, threads=2)
    assert [(e.fitness, e.status, e.terms) for e in together] == [
        (e.fitness, e.status, e.terms) for e in alone
    ]
    assert ontogeny.evaluate_many([], seconds=1) == []


def test_a_direct_genome_develops_as_its_grammar_grows():
    text = "axiom: forward(1) [ revolute forward(0.5) output(1) ] revolute forward(1) output(1)\n"
    a = ontogeny.genome(text, "direct")
    b = ontogeny.grow(text)
    assert a.to_json() == b.to_json()
    assert ontogeny.evaluate(a, seconds=1).fitness == ontogeny.evaluate(b, seconds=1).fitness


def test_arrays_have_the_documented_shapes(root):
    creature = ontogeny.load(root / CHAIN)
    assert creature.sizes.shape == (10, 3)
    assert creature.positions.shape == (10, 3)
    assert creature.orientations.shape == (10, 4)
    assert creature.sizes.dtype == np.float64
    recorded = ontogeny.evaluate(creature, seconds=1, record=True)
    frames = recorded.times.shape[0]
    assert frames > 10
    assert recorded.trajectory.shape == (frames, 10, 3)
    assert np.all(np.diff(recorded.times) > 0)
    plain = ontogeny.evaluate(creature, seconds=1)
    assert plain.trajectory is None and plain.times is None
    assert plain.fitness == recorded.fitness


def test_a_malformed_grammar_raises_value_error_with_its_line_and_column(tmp_path):
    with pytest.raises(ValueError, match=r"<string>:3:4"):
        ontogeny.grow("axiom: A\nderivation length: 2\nA -> A B\n")
    path = tmp_path / "bad.lsys"
    path.write_text("axiom: forward(\n")
    with pytest.raises(ValueError, match=str(path) + r":\d+:\d+"):
        ontogeny.load(path)


def test_a_runaway_grammar_and_nan_parameters_raise_value_error():
    with pytest.raises(ValueError, match="grew past"):
        ontogeny.grow("axiom: A\nderivation length: 100\nA --> A A\n")
    with pytest.raises(ValueError, match="division by zero"):
        ontogeny.grow("axiom: forward(0/0)\n")
    with pytest.raises(ValueError, match="seconds"):
        ontogeny.evaluate(ontogeny.grow(TWO_BOXES), seconds=math.nan)


def test_a_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        ontogeny.load(tmp_path / "nothing.lsys")
    with pytest.raises(FileNotFoundError):
        ontogeny.Run(tmp_path / "no-run")


def test_unknown_names_raise_value_error_listing_the_known_ones():
    creature = ontogeny.grow(TWO_BOXES)
    with pytest.raises(ValueError, match="unknown task 'climb'.*walker"):
        ontogeny.evaluate(creature, "climb")
    with pytest.raises(ValueError, match="^fitness reads speed, which is not a term of the walker task; its terms are D_w, "):
        ontogeny.evaluate(creature, fitness="speed")
    with pytest.raises(ValueError, match="unknown setting"):
        ontogeny.evaluate(creature, setting="coarse")
    with pytest.raises(ValueError, match="unknown encoding"):
        ontogeny.genome("axiom: forward(1)\n", "dna")
    with pytest.raises(ValueError, match="threads"):
        ontogeny.evaluate_many([creature], threads=0)


def test_a_keyword_the_task_does_not_read_raises_value_error_naming_the_task():
    creature = ontogeny.grow(TWO_BOXES)
    with pytest.raises(ValueError, match='^fitness "distance" is a formula of the walker task, not of the jump task'):
        ontogeny.evaluate(creature, "jump", fitness="distance")
    with pytest.raises(ValueError, match="^target= is for the aim task only, and the task is catapult$"):
        ontogeny.evaluate_many([creature], "catapult", target=(3, 0, 0))
    with pytest.raises(ValueError, match="^target= is for the aim task only, and the task is walker$"):
        ontogeny.evaluate(creature, target=(3, 0, 0))


def test_a_file_that_is_not_a_creature_raises_value_error(tmp_path):
    path = tmp_path / "other.json"
    path.write_text('{"hello": 1}')
    with pytest.raises(ValueError, match="not a creature"):
        ontogeny.load(path)


def test_an_evolution_equals_the_command_lines_and_reads_back(tmp_path, cli):
    flags = dict(pop=6, gens=2, seed=3, seconds=1, encoding="direct", setting="fast")
    run = ontogeny.evolve(out=tmp_path / "py", threads=2, **flags)
    cli(
        "evolve", "--out", tmp_path / "cli", "--threads", "1",
        *[a for k, v in flags.items() for a in (f"--{k}", str(v))],
    )
    theirs = cli.json("runs", "show", tmp_path / "cli", "--json")["generations"]
    ours = run.generations()
    assert len(ours) == 2
    assert [g["best"] for g in ours] == [g["best"] for g in theirs]
    assert [g["mean"] for g in ours] == [g["mean"] for g in theirs]
    individuals = run.individuals(1)
    assert len(individuals) == 6
    assert {"fitness", "status", "genome_text", "parts", "terms"} <= set(individuals[0])
    # Generation 1's parents are in generation 0; generation 0 has none.
    assert [i["parents_generation"] for i in individuals] == [0] * 6
    assert [i["parents_generation"] for i in run.individuals(0)] == [None] * 6
    assert len(run.individuals()) == 12
    assert ontogeny.Run(tmp_path / "py").settings()["encoding"] == "direct"
    with pytest.raises(ValueError, match="already holds a run"):
        ontogeny.evolve(out=tmp_path / "py", **flags)


def test_a_run_reads_into_pandas(tmp_path):
    pd = pytest.importorskip("pandas")
    run = ontogeny.evolve(out=tmp_path / "run", pop=6, gens=2, seconds=1, encoding="direct", setting="fast")
    frame = run.to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame["generation"]) == [0, 1]
    assert len(run.to_pandas("individuals")) == 12


def test_a_runs_best_genome_loads_and_evaluates_as_the_command_line(tmp_path, cli):
    ontogeny.evolve(out=tmp_path / "graph", encoding="graph", pop=6, gens=2, seconds=1, setting="fast")
    best = tmp_path / "graph" / "best.json"
    ours = ontogeny.evaluate(ontogeny.load(best), seconds=1, setting="fast")
    theirs = cli.json("eval", best, "--task", "walker", "--seconds", "1", "--setting", "fast", "--json")
    assert (ours.fitness, ours.status) == (theirs["fitness"], theirs["status"])
    text = best.read_text()
    assert ontogeny.genome(text, "graph").to_json() == ontogeny.load(best).to_json()
