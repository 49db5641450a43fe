"""`hexdom mesh PART -o mesh.inp` names the CAD faces: a node set and an element surface Face<k> per
FreeCAD face, usable by CalculiX as FreeCAD's own set-up uses them (*BOUNDARY on one face's nodes,
*DSLOAD on another's surface).

Oracles: FreeCAD makes the box and numbers its faces (Face1 at x = 0, Face2 at x = 40, ...);
meshio reads the .inp and its node sets; CalculiX solves, and the reaction on the fixed face must
balance the pressure times the loaded face's area (equilibrium), first and second order."""

import re
import shutil
import subprocess

import meshio
import numpy as np
import pytest


@pytest.fixture(scope="module")
def box_step(freecad, tmp_path_factory):
    FreeCAD, Part = freecad
    path = tmp_path_factory.mktemp("box") / "box.step"
    box = Part.makeBox(40, 20, 10)
    assert abs(box.Faces[0].Surface.Position.x) < 1e-12 and abs(box.Faces[1].Surface.Position.x - 40) < 1e-12
    box.exportStep(str(path))
    return path


@pytest.mark.parametrize("order", [1, 2])
def test_face_sets_hold_the_face_nodes_and_calculix_loads_them(hexdom_bin, box_step, tmp_path, order):
    out = tmp_path / "box.inp"
    r = subprocess.run([str(hexdom_bin), "mesh", str(box_step), "-o", str(out), "--size", "4", "--order", str(order)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    for k in range(1, 7):
        assert f"*NSET, NSET=Face{k}\n" in text and f"*SURFACE, NAME=Face{k}, TYPE=ELEMENT\n" in text
    m = meshio.read(out)
    axis_of = {1: (0, 0.0), 2: (0, 40.0), 3: (1, 0.0), 4: (1, 20.0), 5: (2, 0.0), 6: (2, 10.0)}
    for k, (axis, value) in axis_of.items():
        on_face = set(np.flatnonzero(np.abs(m.points[:, axis] - value) < 1e-9).tolist())
        assert set(m.point_sets[f"Face{k}"].tolist()) == on_face, k

    if shutil.which("ccx") is None:
        pytest.skip("ccx (calculix-ccx) not installed")
    job = tmp_path / "job.inp"
    job.write_text("*INCLUDE, INPUT=box.inp\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
                   "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*STEP\n*STATIC\n*BOUNDARY\nFace1, 1, 3\n"
                   "*DSLOAD\nFace2, P, -2.0\n*NODE PRINT, NSET=Face1, TOTALS=ONLY\nRF\n*END STEP\n")
    run = subprocess.run(["ccx", "job"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-2000:]
    dat = (tmp_path / "job.dat").read_text()
    match = re.search(r"total force \(fx,fy,fz\) for set FACE1 and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", dat)
    assert match, dat
    force = np.array([float(v) for v in match.groups()])
    # A pull of 2 on the 20 x 10 face at x = 40: the support at x = 0 holds -400 along x.
    np.testing.assert_allclose(force, [-400.0, 0.0, 0.0], atol=1e-6)
