"""One options structure behind `hexdom mesh`, `_hexdom` and the workbench (issue "One pipeline behind
every front end"): the defaults come from the core's header (pipeline::MeshCadOptions) once,
`_hexdom.mesh_options()` gives them to Python, and the program's --help shows the same values; a
failed pipeline hands back what its finished stages made, so that a front end can show them.

Oracles: the program's own --help text (CLI11 prints each option's default), the keyword defaults
Python's inspect reads off the module's functions."""

import inspect
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import HexDomWorkbench.core as wb_core

# (mesh_options key, `hexdom mesh` option whose default --help prints)
CLI_OPTIONS = [("level", "--level"), ("polycube_seconds", "--polycube-seconds"),
               ("edge_weight", "--lambda"), ("max_relabels", "--max-relabels"), ("size", "--size"),
               ("method", "--method"), ("max_size", "--max-size"), ("min_size", "--min-size"),
               ("cells_across", "--cells-across"), ("growth_rate", "--growth-rate")]
# Flags (--help shows no default): their mesh_options value is off.
CLI_FLAGS = [("pillow_curves", "--pillow-curves")]


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
            # (--help prints six significant digits)
            assert float(shown[flag]) == pytest.approx(float(value), rel=1e-5), (key, shown[flag], value)
    text = subprocess.run([str(hexdom_bin), "mesh", "--help"], capture_output=True, text=True, check=True).stdout
    for key, flag in CLI_FLAGS:
        assert re.search(r"^\s+" + re.escape(flag) + r"\b", text, re.M), flag
        assert options[key] is False, key
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


def test_the_size_bounds_give_the_program_s_mesh(core, hexdom_bin, tmp_path):
    """max_size, min_size and cells_across through core.mesh_surface (_hexdom) and through
    `hexdom mesh --max-size --min-size --cells-across` on the same STL box: the same cells, the
    same nodes; a min size above the max size is refused by both."""
    sys_path = str(Path(__file__).resolve().parents[1] / "cli")
    if sys_path not in sys.path:
        sys.path.insert(0, sys_path)
    from test_cli_input_checks import _box, _write_stl
    src = _write_stl(tmp_path / "bar.stl", _box((0, 0, 0), (40.0, 3.0, 1.0)))
    out = tmp_path / "bar.vtk"
    subprocess.run([str(hexdom_bin), "mesh", str(src), "-o", str(out), "--max-size", "0.8",
                    "--min-size", "0.3", "--cells-across", "3"], check=True, capture_output=True)
    cli = core.read_mesh(str(out))
    run = core.mesh_surface(core.read_surface(str(src)), max_size=0.8, min_size=0.3, cells_across=3)
    assert run.mesh.counts == cli.counts
    assert np.abs(run.mesh.V - cli.V).max() < 1e-9
    # Default size 1.34 (diagonal / 30): cells of 0.8 along the bar, 50 of them.
    assert len(np.unique(np.round(cli.V[:, 0], 9))) == 51
    with pytest.raises(core.InputError, match="min size 2 is larger than the max size 1"):
        core.mesh_surface(core.read_surface(str(src)), max_size=1.0, min_size=2.0)


def test_face_sizes_give_the_program_s_mesh(core, hexdom_bin, tmp_path):
    """face_sizes and edge_sizes through core.mesh_part (_hexdom) and `hexdom mesh --face-size /
    --edge-size` on the bundled bracket: the same cells, the same nodes; bad entries refused."""
    step = Path(__file__).resolve().parents[2] / "examples" / "data" / "bracket.step"
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    out = tmp_path / "bracket.vtk"
    subprocess.run([str(hexdom_bin), "mesh", str(step), "-o", str(out), "--face-size", "Face10=1.5"],
                   check=True, capture_output=True)
    cli = core.read_mesh(str(out))
    run = core.mesh_part(str(step), face_sizes={10: 1.5})
    # Auto keeps the mesh whose cells on the hole are within 20% of 1.5 (the polycube's here: its
    # cell made 1.8, the hole's circle on 0.785 of its square), measured as the CLI's log says.
    assert run.method == "polycube" and len(run.local_size_ratios) == 1, (run.method, run.local_size_ratios)
    assert 0.8 <= run.local_size_ratios[0] <= 1.2, run.local_size_ratios
    assert run.mesh.counts == cli.counts
    assert np.abs(run.mesh.V - cli.V).max() < 1e-6
    with pytest.raises(core.InputError, match="the face number must be at least 1 and the size positive"):
        core.mesh_part(str(step), face_sizes={0: 1.0})
    with pytest.raises(core.InputError, match="local size on face 12: the part has no such face"):
        core.mesh_part(str(step), face_sizes={12: 1.0})
    # The polycube path meets them too (its mesh refined by thirds near the face).
    polycube = core.mesh_part(str(step), face_sizes={10: 1.0}, method="polycube")
    assert polycube.method == "polycube"
    assert len(polycube.mesh.types) > 4 * len(core.mesh_part(str(step), method="polycube").mesh.types)
    # Along an edge (Edge20, the hole's top rim) likewise.
    subprocess.run([str(hexdom_bin), "mesh", str(step), "-o", str(out), "--edge-size", "Edge20=1.5"],
                   check=True, capture_output=True)
    cli = core.read_mesh(str(out))
    run = core.mesh_part(str(step), edge_sizes={20: 1.5})
    assert run.mesh.counts == cli.counts
    assert np.abs(run.mesh.V - cli.V).max() < 1e-6
    with pytest.raises(core.InputError, match="Edge25 does not exist"):
        core.mesh_part(str(step), edge_sizes={25: 1.0})
