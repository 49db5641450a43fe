"""Fixtures of the command-line suite; paths come from tests/python/hexdom_test_support.py."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
import hexdom_test_support as support  # noqa: E402


@pytest.fixture(scope="session")
def hexdom_bin():
    """Path of the hexdom program under test (HEXDOM_BUILD_DIR/bin/hexdom)."""
    return support.hexdom_bin()


@pytest.fixture(scope="session")
def data_root():
    """<data>/hexdom; skips (naming the path) when the shared data is absent."""
    if not support.HEXDOM_DATA.is_dir():
        pytest.skip(support.missing(support.HEXDOM_DATA))
    return support.HEXDOM_DATA
