"""One options structure behind `hexdom mesh`, `_hexdom` and the workbench (issue "One pipeline behind
every front end"): the defaults come from the core's header (pipeline::MeshCadOptions) once,
`_hexdom.mesh_options()` gives them to Python, and the program's --help shows the same values; a
failed pipeline hands back what its finished stages made, so that a front end can show them.

Oracles: the program's own --help text (CLI11 prints each option's default), the keyword defaults
Python's inspect reads off the module's functions."""

import inspect
import re
import subprocess

import pytest

import HexDomWorkbench.core as wb_core

# (mesh_options key, `hexdom mesh` option whose default --help prints)
CLI_OPTIONS = [("level", "--level"), ("polycube_seconds", "--polycube-seconds"),
               ("edge_weight", "--lambda"), ("max_relabels", "--max-relabels"), ("size", "--size"),
               ("method", "--method")]


def _help_defaults(hexdom_bin):
    text = subprocess.run([str(hexdom_bin), "mesh", "--help"], capture_output=True, text=True,
                          check=True).stdout
    defaults = {}
    for _, flag in CLI_OPTIONS:
        # "  -s,--level INT:INT in [0 - 6]=1" / "  --lambda,--edge-weight FLOAT=0.1"
        m = re.search(r"^\s+(?:-\w,)?" + re.escape(flag) + r"\b[^\n=]*=(\S+)", text, re.M)
        assert m, "no default shown for {} in `hexdom mesh --help`".format(flag)
        defaults[flag] = m.group(1)
    return defaults


def test_mesh_options_are_the_program_defaults(core, hexdom_bin):
    options = core._hexdom.mesh_options()
    shown = _help_defaults(hexdom_bin)
    for key, flag in CLI_OPTIONS:
        value = options[key]
        if isinstance(value, str):
            assert shown[flag] == value, (key, shown[flag], value)
        else:
            assert float(shown[flag]) == pytest.approx(float(value)), (key, shown[flag], value)
    assert options["improve"] is True and options["snap"] is True and options["align"] is True
    assert options["target_edge_ratio"] == wb_core.TARGET_EDGE_RATIO


def test_python_keyword_defaults_are_the_core_s(core):
    options = core.mesh_options()
    for fn in (core.mesh_surface, core.mesh_part, core._hexdom.mesh_surface, core._hexdom.mesh_cad):
        try:
            params = inspect.signature(fn).parameters
        except (TypeError, ValueError):  # a pybind11 function: its defaults are in its docstring
            doc = fn.__doc__ or ""
            for key in ("level", "edge_weight", "max_relabels", "relax_sweeps"):
                m = re.search(r"\b" + key + r": \w+ = ([^,)]+)", doc)
                assert m, (fn.__name__, key)
                assert float(m.group(1)) == pytest.approx(float(options[key])), (fn.__name__, key)
            continue
        for key in ("level", "edge_weight", "max_relabels", "relax_sweeps", "improve", "method"):
            if key in params:
                assert params[key].default == options[key], (fn.__name__, key)


def test_a_failed_pipeline_hands_back_its_finished_stages(core):
    """A tetrahedron (no face near an axis plane) with the polycube path forced: the error names
    the stage and carries the tessellation and the segmentation that were made."""
    if not core._hexdom.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    brep = _tetrahedron_brep()
    with pytest.raises(core.Error) as info:
        core.mesh_part(brep, size=20.0, level=2, method="polycube")
    e = info.value
    assert e.stage == "autopolycube", e.stage
    assert e.run is not None and len(e.run.surface.F) > 0
    assert len(e.run.labels.F) == len(e.run.surface.F)
    assert set(int(v) for v in e.run.labels.patch) <= set(range(1, 7))
    assert "chart" in str(e)


def _tetrahedron_brep():
    import sys
    for p in ("/usr/lib/freecad-python3/lib",):
        if p not in sys.path:
            sys.path.append(p)
    try:
        import FreeCAD
        import Part
    except ImportError:
        pytest.skip("FreeCAD's Part (freecad-python3) is needed to build the part")
    pts = [FreeCAD.Vector(*p) for p in ((0, 0, 0), (10, 1, 2), (3, 9, 1), (4, 3, 11))]
    faces = [Part.Face(Part.makePolygon([pts[a], pts[b], pts[c], pts[a]]))
             for a, b, c in ((0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3))]
    return Part.makeSolid(Part.makeShell(faces)).exportBrepToString()
