"""Shared fixtures: the repository's files and the command-line binary the package's results
are compared with (``ONTOGENY_BIN``, default ``target/release/ontogeny``)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """Runs the command line; returns its standard output (it must succeed)."""
    binary = Path(os.environ.get("ONTOGENY_BIN", ROOT / "target" / "release" / "ontogeny"))
    if not binary.is_file():
        pytest.skip(f"no ontogeny binary at {binary}: build it or set ONTOGENY_BIN")

    def run(*args: str) -> str:
        done = subprocess.run(
            [str(binary), *map(str, args)], capture_output=True, text=True, cwd=ROOT
        )
        assert done.returncode == 0, done.stderr
        return done.stdout

    run.json = lambda *args: json.loads(run(*args))
    return run


@pytest.fixture
def write_config(tmp_path):
    """Writes a configuration's text to a file named ``name`` in the test's folder; its path."""

    def write(name: str, text: str) -> Path:
        path = tmp_path / name
        path.write_text(text)
        return path

    return write
