"""Fixtures of the Python suites: shared data root, hexdom program, HexDomWorkbench.core, FreeCAD.

The paths and the skip helper live in hexdom_test_support (also used by tests/cli)."""

import sys

import pytest

import hexdom_test_support as support


@pytest.fixture(scope="session")
def data_root():
    """<data>/hexdom; skips (naming the path) when the shared data is absent."""
    if not support.HEXDOM_DATA.is_dir():
        pytest.skip(support.missing(support.HEXDOM_DATA))
    return support.HEXDOM_DATA


@pytest.fixture(scope="session")
def hexdom_bin():
    """Path of the hexdom program under test (HEXDOM_BUILD_DIR/bin/hexdom)."""
    return support.hexdom_bin()


@pytest.fixture(scope="session")
def core():
    """HexDomWorkbench.core over the _hexdom module of the build under test."""
    return support.load_core()


FREECAD_PATHS = ["/usr/lib/freecad-python3/lib", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"]


@pytest.fixture(scope="session")
def freecad():
    """(FreeCAD, Part) from FreeCAD's Python modules (an oracle for CAD volumes and distances), or a
    skip when they are not installed."""
    for p in FREECAD_PATHS:
        if p not in sys.path:
            sys.path.append(p)
    try:
        import FreeCAD
        import Part
    except ImportError as e:
        pytest.skip(f"FreeCAD not importable from {FREECAD_PATHS}: {e}")
    return FreeCAD, Part
