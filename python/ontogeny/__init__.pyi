"""Type stubs of the ``ontogeny`` package (the compiled ``ontogeny._ontogeny`` and its
pure-Python helpers)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike]
_Env = Optional[Sequence[Tuple[int, float]]]
_Task = Literal["walker", "jump", "catapult", "aim", "stand", "swim"]
# The walker's formulas; any other string is an expression of the task's terms
# (``"D_w - 0.5 * drag"``).
_Fitness = Literal[
    "normalised",
    "distance",
    "iterative-move",
    "box-lover",
    "fat-lover",
    "dwarf-slayer",
    "hornby-pollack",
]

_Sim = Dict[str, Union[float, int, str, bool]]
"""The simulator's knobs, by their ``[task.sim]`` keys in a configuration file, set over the
named ``setting``: ``control_step`` (older files: ``dt``), ``substeps``,
``solver_iterations``, ``pgs_iterations``, ``rest_substeps``, ``rest_solver_iterations``,
``joints``, ``self_collision``, ``friction``, ``actuator``, ``strength``, ``strength_from``,
``muscle_speed``, ``max_speed``, ``drop_height``, ``explosion_distance``, ``speed_limit``,
``energy_tolerance``."""

TASKS: Dict[str, str]
"""Every task by name, with what it measures, in the order ``ontogeny eval --help`` lists
them."""

class Creature:
    """A creature: box parts joined by joints, and a brain."""

    @property
    def parts(self) -> int:
        """The number of parts (boxes)."""
    @property
    def joints(self) -> int:
        """The number of joints."""
    @property
    def neurons(self) -> int:
        """The number of neurons."""
    @property
    def sizes(self) -> npt.NDArray[np.float64]:
        """Each part's edge lengths (length, thickness, width), metres: parts × 3."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """Each part's centre (metres; y is up): parts × 3."""
    @property
    def orientations(self) -> npt.NDArray[np.float64]:
        """Each part's orientation, a unit quaternion (w, x, y, z): parts × 4."""
    @property
    def valid(self) -> bool:
        """Whether it has parts and its development reported no error."""
    @property
    def problems(self) -> List[str]:
        """The problems development reported, one line each."""
    @property
    def notes(self) -> List[str]:
        """Notes and warnings from growing it, one line each."""
    def to_json(self) -> str:
        """The creature as JSON (``creature.json``)."""

class Evaluation:
    """The outcome of an evaluation."""

    @property
    def task(self) -> str: ...
    @property
    def fitness(self) -> float:
        """The fitness; -999999 unless the status is ``ok`` (0 for a walker that never came to rest)."""
    @property
    def status(self) -> str:
        """``ok``, ``unstable``, ``exploded``, ``self-intersecting``, ``too-tall`` or
        ``invalid``."""
    @property
    def terms(self) -> Dict[str, float]:
        """The terms behind the fitness, by name."""
    @property
    def message(self) -> Optional[str]:
        """What went wrong, when something did."""
    @property
    def habitats(self) -> List[Dict[str, Any]]:
        """Each habitat's and trial's walk (``name``, ``trial``, ``parts``, ``joints``,
        ``fitness``, ``status``, ``terms``, ``message`` when something went wrong), as
        ``ontogeny eval --json`` lists them; empty for a task without habitats or trials."""
    @property
    def trajectory(self) -> Optional[npt.NDArray[np.float64]]:
        """Every part's centre at each recorded moment: frames × parts × 3 (``record=True``);
        parts counts every part the body had at any moment, and a part that appeared during
        the walk (``develop = "during"``) has NaN rows before it appeared."""
    @property
    def times(self) -> Optional[npt.NDArray[np.float64]]:
        """The simulated time of each recorded moment, seconds (``record=True``)."""
    def to_json(self) -> str:
        """As ``ontogeny eval --json`` prints it."""

def grow(
    text: str,
    *,
    steps: Optional[int] = None,
    time: Optional[float] = None,
    dt: Optional[float] = None,
    grammar_seed: Optional[int] = None,
    env: _Env = None,
    defines: Optional[Dict[str, float]] = None,
    seed: Optional[int] = None,
) -> Creature:
    """Grows grammar text to its last frame, as ``ontogeny grow`` does. ``defines`` sets
    the grammar's defines as ``--define NAME=VALUE`` does (``defines={"GROWTH": 1.5}``),
    ``grammar_seed`` its seed as ``--grammar-seed`` does (``seed`` is its old name, read with
    a ``DeprecationWarning``)."""

def load(
    path: _Path,
    *,
    steps: Optional[int] = None,
    time: Optional[float] = None,
    dt: Optional[float] = None,
    grammar_seed: Optional[int] = None,
    env: _Env = None,
    defines: Optional[Dict[str, float]] = None,
    seed: Optional[int] = None,
) -> Creature:
    """Reads a creature from an ``.lsys``, a ``creature.json`` or a graph genome's
    ``.json``, as ``ontogeny eval FILE`` does; ``defines`` sets an ``.lsys`` file's defines
    as ``--define NAME=VALUE`` does, ``grammar_seed`` its seed as ``--grammar-seed`` does
    (``seed`` is its old name, read with a ``DeprecationWarning``)."""

def genome(text: str, encoding: str = "direct", *, seed: int = 0) -> Creature:
    """Develops a genome's text (``direct``: an axiom alone; ``lsystem``, ``continuous``:
    ``best.lsys``; ``graph``: ``best.json``) within the encoding's default limits."""

def genome_habitats(config: _Path, genome: _Path) -> Dict[str, Any]:
    """Develops the genome file ``genome`` in each habitat of the configuration ``config``
    (its ``[[task.habitats]]``, each with its chemical array) and returns what ``ontogeny
    genome show --habitats CONFIG GENOME --json`` prints: ``file``, ``encoding``,
    ``habitats`` (each ``name``, ``environment``, ``develops``, ``creature``, ``error``),
    ``differences`` (each pair's ``from``, ``to``, ``same``, counts, ``volume``, ``resized``,
    ``largest_resize``, ``summed_resize``, ``moved``, ``joints_of_another_kind``, ``text``),
    ``depends_on_habitat`` and ``verdict``."""

def derive(
    text: str,
    *,
    steps: Optional[int] = None,
    time: Optional[float] = None,
    dt: Optional[float] = None,
    grammar_seed: Optional[int] = None,
    env: _Env = None,
    defines: Optional[Dict[str, float]] = None,
    seed: Optional[int] = None,
) -> List[Tuple[float, str, List[float]]]:
    """The frames ``(time, modules, env)`` of the derivation, the axiom first (``defines``
    sets the grammar's defines, as ``--define`` does; ``grammar_seed`` its seed, as
    ``--grammar-seed`` does, ``seed`` being its old name). A derivation
    that reaches a fixed point stops there: the frames to it, then the last frame, with a
    warning that says so."""

def evaluate(
    creature: Union[Creature, _Path],
    task: _Task = "walker",
    *,
    seconds: Optional[float] = None,
    fitness: Optional[Union[_Fitness, str]] = None,
    setting: str = "default",
    sim: Optional[_Sim] = None,
    target: Optional[Tuple[float, float, float]] = None,
    config: Optional[_Path] = None,
    habitat: Optional[str] = None,
    record: bool = False,
) -> Evaluation:
    """Evaluates a creature on a task, as ``ontogeny eval --task TASK`` does; ``sim`` sets the
    simulator's knobs by their ``[task.sim]`` keys (see ``_Sim``) over ``setting``. The task's
    keywords: ``seconds`` (the walker, jump, catapult, aim, stand and swim tasks), ``fitness``
    (the walker, jump, catapult, aim, stand and swim tasks), ``target`` (the aim task); one the
    task does not read raises ValueError. ``fitness`` is one of the walker's formulas or an
    expression of the task's terms (``"D_w - 0.5 * drag"``); an unknown term raises
    ValueError. ``config`` takes the task from a configuration file's ``[task]`` tables
    instead (its habitats and trials too, as ``ontogeny eval --config`` does: the walks are in
    ``Evaluation.habitats``), and ``habitat`` walks in the habitat of that name alone. Given a
    file's path (an ``.lsys`` grammar or a genome) in place of a creature, the file is grown in
    each habitat from the habitat's chemical array, as ``ontogeny eval FILE --config`` grows
    it; a creature already grown in a habitat that sets the array raises ValueError."""

def evaluate_many(
    creatures: Sequence[Creature],
    task: _Task = "walker",
    *,
    threads: Optional[int] = None,
    seconds: Optional[float] = None,
    fitness: Optional[Union[_Fitness, str]] = None,
    setting: str = "default",
    sim: Optional[_Sim] = None,
    target: Optional[Tuple[float, float, float]] = None,
    config: Optional[_Path] = None,
    habitat: Optional[str] = None,
    record: bool = False,
) -> List[Evaluation]:
    """Evaluates creatures in parallel without the GIL; results in order, equal to
    ``evaluate``'s one by one. The task's keywords are ``evaluate``'s."""

class Run:
    """A run directory's records, read read-only."""

    def __init__(self, path: _Path) -> None: ...
    @property
    def path(self) -> str: ...
    def settings(self) -> Dict[str, Any]:
        """``encoding``, ``task``, ``seed``, ``version`` and ``config``."""
    def generations(self) -> List[Dict[str, Any]]:
        """Every generation's record, a dict each."""
    def individuals(self, generation: Optional[int] = None) -> List[Dict[str, Any]]:
        """One generation's individuals (default: every generation's), a dict each; in a run
        with habitats or trials, ``habitats`` lists each one's walks as
        ``Evaluation.habitats`` does."""
    def habitats(self, generation: Optional[int] = None, rank: int = 1) -> List[Dict[str, Any]]:
        """The walks of the individual of rank ``rank`` (1 = the best) in ``generation``
        (default: the last complete one), as ``ontogeny replay --gen --rank`` picks it: each
        habitat's and trial's fitness, status and terms from its stored evaluation; empty in a
        run without habitats or trials."""
    def to_pandas(self, table: str = "generations") -> Any:
        """``"generations"`` or ``"individuals"`` as a pandas ``DataFrame``."""

def evolve(config: Optional[_Path] = None, *, out: _Path, **overrides: Any) -> Run:
    """Runs an evolution into ``out``, as ``ontogeny evolve`` does; ``overrides`` are its
    flags by long name (``gens=3``, ``pop=6``, ``seed=1``, ``encoding="direct"``,
    ``target=(3, 0, 0)``, ...)."""

def resume(
    path: _Path,
    *,
    gens: Optional[int] = None,
    threads: Optional[int] = None,
    progress: bool = False,
) -> Run:
    """Goes on with the run in ``path`` (interrupted, or finished and extended to ``gens``
    generations), as ``ontogeny evolve --resume PATH`` does."""
