"""Fixtures for the App tests, which run under FreeCAD's Python (see run_app_tests.py)."""

import itertools
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

FreeCAD = pytest.importorskip("FreeCAD", reason="App tests run inside freecadcmd (run.sh)")

_counter = itertools.count()


@pytest.fixture
def doc():
    """A fresh document, closed after the test."""
    name = "HexDomTest{}".format(next(_counter))
    d = FreeCAD.newDocument(name)
    yield d
    if name in FreeCAD.listDocuments():  # tests that reopen a file close this one themselves
        FreeCAD.closeDocument(name)


@pytest.fixture
def artifacts_dir():
    path = os.environ.get("HEXDOM_FC_ARTIFACTS",
                          os.path.join(os.path.dirname(os.path.abspath(__file__)), "artifacts"))
    os.makedirs(path, exist_ok=True)
    return path


def reopen(document, path):
    """Saves ``document`` to ``path``, closes it and opens the file again."""
    document.saveAs(path)
    FreeCAD.closeDocument(document.Name)
    return FreeCAD.openDocument(path)
