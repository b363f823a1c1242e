"""Ontogeny from Python: grow virtual creatures from L-systems, evaluate them in physics and
evolve them, with the Rust engine of the ``ontogeny`` command line.

Results are the command line's, bit for bit: ``ontogeny.evaluate(ontogeny.load(path))`` gives
the fitness ``ontogeny eval PATH --task walker --json`` prints. Bad input raises
``ValueError`` (with the file, line and column of a grammar), a missing file
``FileNotFoundError``. Ctrl-C stops a long call (``grow``, ``derive``, ``evaluate``,
``evaluate_many``, ``evolve``, ``resume``) within a fraction of a second with
``KeyboardInterrupt``; an interrupted evolution goes on with ``resume``.
"""

from __future__ import annotations

from os import PathLike
from typing import Any, Optional, Union

from ._ontogeny import (
    Creature,
    Evaluation,
    TASKS,
    Run as _Run,
    __version__,
    derive,
    evaluate,
    evaluate_many,
    genome,
    genome_habitats,
    grow,
    load,
)
from ._ontogeny import evolve as _evolve
from ._ontogeny import resume as _resume

__all__ = [
    "Creature",
    "Evaluation",
    "Run",
    "TASKS",
    "__version__",
    "derive",
    "evaluate",
    "evaluate_many",
    "evolve",
    "genome",
    "genome_habitats",
    "grow",
    "load",
    "resume",
]


class Run(_Run):
    """A run directory's records (``run.sqlite``), read read-only.

    ``generations()`` and ``individuals(generation=None)`` return lists of dicts;
    ``to_pandas()`` returns them as a pandas ``DataFrame`` (pandas must be installed).
    """

    def to_pandas(self, table: str = "generations"):
        """The run's ``"generations"`` (one row per generation, the default) or
        ``"individuals"`` (one row per individual of every generation) as a pandas
        ``DataFrame``."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Run.to_pandas needs pandas: pip install pandas") from e
        if table == "generations":
            rows = self.generations()
            for row in rows:
                fine = row.pop("best_fine", None) or {}
                row["best_fine"] = fine.get("fitness")
                row["best_fine_status"] = fine.get("status")
            return pd.DataFrame(rows).rename(columns={"index": "generation"})
        if table == "individuals":
            return pd.DataFrame(self.individuals())
        raise ValueError(f"unknown table '{table}' (generations or individuals)")


def evolve(
    config: Optional[Union[str, PathLike]] = None,
    *,
    out: Union[str, PathLike],
    **overrides: Any,
) -> Run:
    """Runs an evolution into the directory ``out`` (refused if it holds a run), as
    ``ontogeny evolve --out OUT [--config CONFIG]`` does, and returns the :class:`Run`.

    ``overrides`` are the command line's flags by their long name: ``encoding``, ``task``,
    ``fitness``, ``preset``, ``pop``, ``gens`` (or ``walks``, a budget of walks), ``seed``,
    ``seconds``, ``setting``,
    ``threads``, ``init``, and ``verify_best=False`` / ``cache=False`` for
    ``--no-verify-best`` / ``--no-cache``; ``progress=True`` prints a line per generation on
    standard error. The results do not depend on ``threads``.

    Ctrl-C stops it with ``KeyboardInterrupt``, dropping the generation under way; the run
    keeps every generation stored before it, and :func:`resume` goes on from there.
    """
    return Run(_evolve(config, out=out, **overrides))


def resume(
    path: Union[str, PathLike],
    *,
    gens: Optional[int] = None,
    threads: Optional[int] = None,
    progress: bool = False,
) -> Run:
    """Goes on with the run in the directory ``path``, as ``ontogeny evolve --resume PATH
    [--gens GENS]`` does, and returns the :class:`Run`: from its last stored generation (after
    Ctrl-C or a kill) to its last one, or to ``gens`` generations in all, which extends a
    finished run. It ends exactly as an uninterrupted run would, whatever ``threads``.
    """
    return Run(_resume(path, gens=gens, threads=threads, progress=progress))
