"""Paths the meson test passes (CANTACT_CLI, CANTACT_LAYOUT, CANTACT_SOURCE) as fixtures."""
import os
import subprocess

import pytest


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} not set (run the suite through meson test)")
    return value


@pytest.fixture(scope="session")
def cli():
    return _env("CANTACT_CLI")


@pytest.fixture(scope="session")
def source():
    return _env("CANTACT_SOURCE")


@pytest.fixture(scope="session")
def layout():
    return _env("CANTACT_LAYOUT")


@pytest.fixture
def run_cli(cli, tmp_path):
    """Runs `cantact ARGS...`; returns the path of the output written with -o."""

    def run(*args, name="out.csv"):
        out = tmp_path / name
        subprocess.run([cli, *args, "-q", "-o", str(out)], check=True)
        return out

    return run
