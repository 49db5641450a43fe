"""End to end with CalculiX: a cantilever Part::Box meshed by HexDom (hexes, wedges, both), fixed
at x = 0 and loaded at x = L through FEM constraints on the box faces, solved with ccx.

Oracles: axial end displacement F L / (E A) within 2%; transverse tip deflection
F L^3 / (3 E I) within 10% (linear hexes lock in bending: about 3.5% stiff at 4 elements through
the thickness). Measured figures go to artifacts/fem_results.txt for run.sh's summary.
"""

import os
import shutil

import numpy as np
import pytest

import FreeCAD
from HexDomWorkbench import core, make
from HexDomWorkbench.convert import fem_setup

import fc_fem
import fc_testdata

L, W, H = 100.0, 10.0, 10.0  # mm
NX, NY, NZ = 40, 4, 4
E, NU, F = 210000.0, 0.3, 1000.0  # MPa, -, N
AXIAL = F * L / (E * W * H)
BENDING = F * L ** 3 / (3.0 * E * W * H ** 3 / 12.0)

VARIANTS = {"hex": 0, "wedge": NZ, "mixed": NZ // 2}  # wedge layers from the bottom
pytestmark = pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX ccx not on PATH")


def _inp_sets(inp_path):
    """(nodes in the fixed node set, {node: load} of *CLOAD) from the written input file."""
    fixed, loads, section = [], {}, None
    for line in open(inp_path):
        line = line.strip()
        if line.startswith("**") or not line:
            continue
        if line.startswith("*"):
            upper = line.upper()
            section = ("fixed" if upper.startswith("*NSET,NSET=CONSTRAINTFIXED")
                       else "cload" if upper.startswith("*CLOAD") else None)
            continue
        if section == "fixed":
            fixed += [int(t) for t in line.split(",") if t.strip()]
        elif section == "cload":
            node, _dof, value = line.split(",")
            loads[int(node)] = loads.get(int(node), 0.0) + float(value)
    return fixed, loads


def solve(doc, tmp_path, wedge_layers, load):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = L, W, H
    doc.recompute()
    analysis, solver, _ = fc_fem.static_analysis(
        doc, E, NU, [(box, "Face1")], [(box, "Face2")], F,  # fixed at x = 0, loaded at x = L
        (box, ["Face2"] if load == "axial" else ["Face6"]))  # +x or +z
    V, cells, types = fc_testdata.box_mesh(L, W, H, NX, NY, NZ, wedge_layers)
    mesh = core.Mesh(V, cells, types, np.zeros(len(types), np.int32))
    obj = make.make_hex_mesh(doc, mesh, "HexDomMesh")
    fem_setup.add_to_analysis(analysis, obj)
    doc.recompute()
    assert obj.InvertedCount == 0

    work = tmp_path / "ccx"
    work.mkdir()
    fea = fc_fem.write_inp(analysis, solver, work)
    disp = fc_fem.solve(fea, analysis)
    tip = [i + 1 for i, p in enumerate(V) if p[0] == L]
    axis = 0 if load == "axial" else 2
    u = float(np.mean([disp[n][axis] for n in tip]))
    fixed_nodes, loads = _inp_sets(fea.inp_file_name)
    return u, fixed_nodes, loads, obj, box


@pytest.fixture(scope="module")
def report_lines(request):
    lines = []
    yield lines
    path = os.environ.get("HEXDOM_FC_ARTIFACTS",
                          os.path.join(os.path.dirname(os.path.dirname(__file__)), "artifacts"))
    os.makedirs(path, exist_ok=True)
    with open(os.path.join(path, "fem_results.txt"), "w") as f:
        f.write("cantilever {}x{}x{} mm, {}x{}x{} cells, E={} MPa, nu={}, F={} N\n".format(
            L, W, H, NX, NY, NZ, E, NU, F))
        f.write("\n".join(lines) + "\n")


@pytest.mark.parametrize("variant", sorted(VARIANTS))
@pytest.mark.parametrize("load", ["axial", "transverse"])
def test_cantilever(doc, tmp_path, variant, load, report_lines):
    u, fixed_nodes, loads, obj, box = solve(doc, tmp_path, VARIANTS[variant], load)
    theory, tol = (AXIAL, 0.02) if load == "axial" else (BENDING, 0.10)
    err = (u - theory) / theory
    counts = "{} hex + {} prism".format(obj.HexCount, obj.PrismCount)
    line = "{:<6} {:<10} ({:<17}) u = {:.6g} mm, theory {:.6g} mm, error {:+.2f}%".format(
        variant, load, counts, u, theory, 100.0 * err)
    report_lines.append(line)
    FreeCAD.Console.PrintMessage(line + "\n")
    # Every node of the end faces is found by the constraints (they look within 1e-7 of the face).
    face_nodes = (NY + 1) * (NZ + 1)
    assert len(set(fixed_nodes)) == face_nodes
    assert len(loads) == face_nodes
    assert sum(loads.values()) == pytest.approx(F, rel=1e-6)
    assert len(obj.FemMesh.getNodesByFace(box.Shape.Faces[0])) == face_nodes
    assert abs(err) <= tol, line
