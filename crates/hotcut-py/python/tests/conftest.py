"""Shared fixtures of the Python tests: the repository, the CLI they compare against."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[4]
JOBS = REPO / "jobs"


@pytest.fixture(scope="session")
def cli():
    """The hotcut command-line tool (HOTCUT_BIN, else target/{debug,release}/hotcut)."""
    given = os.environ.get("HOTCUT_BIN")
    candidates = [pathlib.Path(given)] if given else [
        REPO / "target" / "debug" / "hotcut",
        REPO / "target" / "release" / "hotcut",
    ]
    for c in candidates:
        if c.is_file():
            return c
    pytest.fail(
        "no hotcut binary: build it with `cargo build -p hotcut` or set HOTCUT_BIN "
        f"(looked at {', '.join(map(str, candidates))})"
    )


def run_cli(cli, job, out):
    """Runs `hotcut run job --out out`, returns the completed process."""
    return subprocess.run(
        [str(cli), "run", str(job), "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
