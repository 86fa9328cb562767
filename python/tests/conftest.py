"""Shared helpers of the Python tests (CTest label `python`; run from the repository root with
PYTHONPATH=<build>/python, FDEM_CLI=<build>/fdem, as python/CMakeLists.txt sets them)."""
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def example(name):
    return str(ROOT / "examples" / name / "scenario.toml")


def cli():
    path = os.environ.get("FDEM_CLI")
    if not path:
        pytest.fail("FDEM_CLI is not set: run the tests through ctest (python/CMakeLists.txt)")
    return path


def cli_run(args, cwd=None):
    """Run the fdem command line; returns (exit code, stdout, stderr)."""
    p = subprocess.run([cli(), *args], capture_output=True, text=True, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def cli_hash(scenario, end_time, out_dir):
    rc, out, err = cli_run(["run", scenario, "--end-time", repr(end_time), "--quiet",
                            "--print-hash", "--out", str(out_dir)])
    assert rc == 0, err
    line = [ln for ln in out.splitlines() if ln.startswith("hash ")]
    assert line, out
    return line[0].split()[1]
