"""Shared fixtures: the CLI binary (``JBEARING_CLI``, set by scripts/test_python.sh) and a runner."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
CASES = HERE / "cases"
REPO = HERE.parent.parent


@pytest.fixture(scope="session")
def cli() -> Path:
    exe = os.environ.get("JBEARING_CLI")
    if not exe:
        pytest.fail(
            "JBEARING_CLI is not set: run the tests through scripts/test_python.sh, or set it to "
            "the jbearing binary built from this checkout"
        )
    path = Path(exe)
    assert path.is_file(), f"JBEARING_CLI={exe} is not a file"
    return path


@pytest.fixture(scope="session")
def run_cli(cli):
    def run(*args: str | os.PathLike) -> str:
        env = dict(os.environ, NO_COLOR="1")
        env.pop("RUST_LOG", None)
        p = subprocess.run(
            [os.fspath(cli), *map(os.fspath, args)],
            capture_output=True,
            text=True,
            env=env,
            cwd=REPO,
        )
        assert p.returncode == 0, f"jbearing {args} failed:\n{p.stdout}\n{p.stderr}"
        return p.stdout

    return run
