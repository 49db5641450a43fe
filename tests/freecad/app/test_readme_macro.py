"""README.md's macro (the python block after <!-- readme-macro -->) runs as written: a STEP part
meshed by hexdom.mesh_part, an analysis with a fixed face, a force, steel and CalculiX, solved.
So the README cannot rot. Checks on what it leaves: constraint node counts are non-zero, fixed
nodes do not move, and the pulled top of the upright rises by at least the stretch of the
upright alone (F L / (E A), L = 40 mm above the base) but not ten times more."""

import os
import re
import shutil

import pytest

import FreeCAD

TEST_DIR = os.environ.get("HEXDOM_FC_TEST_DIR") or os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.abspath(os.path.join(TEST_DIR, "..", ".."))
README = os.path.join(REPO, "README.md")


def macro():
    text = open(README, encoding="utf-8").read()
    found = re.search(r"<!-- readme-macro -->\s*```python\n(.*?)```", text, re.S)
    assert found, "README.md has no python block after <!-- readme-macro -->"
    return found.group(1)


def test_readme_has_the_macro():
    code = macro()
    for needed in ("hexdom.mesh_part(", "makeConstraintFixed", "makeConstraintForce",
                   "makeMaterialSolid", "makeSolverCalculixCcxTools", "ccx_run"):
        assert needed in code, needed
    compile(code, "README.md", "exec")


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX ccx not on PATH")
def test_readme_macro_runs(monkeypatch):
    monkeypatch.chdir(REPO)
    namespace = {"__name__": "__main__"}
    exec(compile(macro(), "README.md macro", "exec"), namespace)
    doc = namespace["doc"]
    try:
        mesh, part = namespace["mesh"], namespace["part"]
        assert mesh.InvertedCount == 0 and mesh.HexCount > 0
        fixed_nodes = mesh.FemMesh.getNodesByFace(part.Shape.getElement(namespace["bottom"]))
        top_nodes = namespace["top_nodes"]
        assert len(fixed_nodes) > 0 and len(top_nodes) > 0
        displacement = namespace["displacement"]
        assert max(displacement[n].Length for n in fixed_nodes) == 0.0
        stretch = 1000.0 * 40.0 / (210000.0 * 10.0 * 40.0)
        uz = namespace["uz"]
        FreeCAD.Console.PrintMessage("README macro: uz = {:.4g} mm, upright alone {:.4g} mm\n"
                                     .format(uz, stretch))
        assert stretch <= uz <= 10 * stretch
    finally:
        FreeCAD.closeDocument(doc.Name)
