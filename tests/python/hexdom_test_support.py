"""Where the tests find things: the repository, the build under test, the shared paper data.

Environment:
  HEXDOM_DATA       root of the shared data (default: ../shared/data beside the repository);
                    tests needing a file of it skip, naming the missing path, when it is absent.
  HEXDOM_BUILD_DIR  CMake build directory holding bin/hexdom and python/_hexdom (default: build).

Imported by tests/python/conftest.py and tests/cli/conftest.py (a module of its own, so that test
modules never have to import a conftest).
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))  # HexDomWorkbench is imported from the working tree

BUILD_DIR = Path(os.environ.get("HEXDOM_BUILD_DIR") or REPO / "build").resolve()
# core.py looks for _hexdom through HEXDOM_BUILD_DIR: make the default explicit.
os.environ["HEXDOM_BUILD_DIR"] = str(BUILD_DIR)
HEXDOM_BIN = BUILD_DIR / "bin" / "hexdom"
DATA_ROOT = Path(os.environ.get("HEXDOM_DATA") or REPO.parent / "shared" / "data").resolve()
HEXDOM_DATA = DATA_ROOT / "hexdom"


# The paper models with a hand-built structure: model -> (segmented patch file, structure with
# prism and tet blocks), both under HEXDOM_DATA/<model>/.
PAPER_MODELS = {
    "rockerarm": ("rockerarm_indexPatch_hexdom.k", "rockerarm_polycube_withtet.k"),
    "mount1": ("mount1_patch_hexdom.k", "mount1_polycube_hexdom_withtet.k"),
    "hepta": ("hepta_patch_hexdom.k", "hepta_polycube_withtet.k"),
    "fertility": ("fertility_indexPatch_hexdom.k", "fertility_polycube_hexdom_withtet.k"),
    "ant": ("ant_indexPatch_hexdom.k", "ant_polycube_withtet.k"),
    "mountwithhole": ("mountwithhole_patch_hexdom.k", "mountwithhole_polycube_withtet.k"),
}


def thin_wedge(layers=3):
    """A thin wedge prism (cross-section a 15 degree kite-like hexagon in xy, apex at x = 10, 4
    high in z) whose two long sides, patches 1 and 2 (normals 165 degrees apart, nearest +Y and
    -Y), share the apex edge; patch 3 the back, 4 the top fan, 5 the bottom fan.
    Returns V (#V x 3 float), F (#F x 3), patch id per triangle."""
    import numpy as np
    h = 10 * np.tan(np.radians(7.5))
    ring = [(0, -h), (5, -h / 2), (10, 0), (5, h / 2), (0, h), (0, 0)]
    side = [1, 1, 2, 2, 3, 3]
    n = len(ring)
    V = [(x, y, 4.0 * k / layers) for k in range(layers + 1) for x, y in ring]
    V += [(10 / 3, 0, 0), (10 / 3, 0, 4.0)]
    tris = []
    for k in range(layers):
        for i in range(n):
            j = (i + 1) % n
            a, b, c, d = k * n + i, k * n + j, (k + 1) * n + j, (k + 1) * n + i
            tris += [(side[i], (a, b, c)), (side[i], (a, c, d))]
    bottom, top = len(V) - 2, len(V) - 1
    for i in range(n):
        j = (i + 1) % n
        tris += [(4, (layers * n + i, layers * n + j, top)), (5, (j, i, bottom))]
    return np.array(V, float), np.array([t for _, t in tris]), np.array([p for p, _ in tris])


def write_k_surface(path, V, F, part):
    """Writes triangles F over vertices V as an LS-DYNA keyword file, one *ELEMENT_SHELL line per
    triangle (part id `part[i]`, the last node repeated) and the *NODE block; returns path."""
    with open(path, "w") as f:
        f.write("*KEYWORD\n*ELEMENT_SHELL\n")
        for e, (pid, t) in enumerate(zip([int(x) for x in part], [[int(i) for i in t] for t in F])):
            f.write(f"{e + 1},{pid},{t[0] + 1},{t[1] + 1},{t[2] + 1},{t[2] + 1}\n")
        f.write("*NODE\n" + "".join(f"{i + 1},{float(x)!r},{float(y)!r},{float(z)!r}\n"
                                    for i, (x, y, z) in enumerate(V)) + "*END\n")
    return path


def island(editor, patch_id=5):
    """Triangles around a triangle in the middle of ``patch_id`` touching no other patch, for a
    PatchEditor (HexDomWorkbench.logic.patch_editing) to plant a patch inside another: the one
    helper of tests/freecad/fc_testdata.py, which the GUI tests use too."""
    sys.path.insert(0, str(REPO / "tests" / "freecad"))
    import fc_testdata
    return fc_testdata.island(editor, patch_id)


def missing(path):
    return f"shared data missing: {path} (set HEXDOM_DATA)"


def data_file(rel):
    """Path of a shared data file (relative to <data>/hexdom); skips the test when it is absent."""
    path = HEXDOM_DATA / rel
    if not path.exists():
        pytest.skip(missing(path))
    return path


def data_params(pattern, exclude=()):
    """One pytest.param per shared data file matching a glob under <data>/hexdom, with its relative
    path as the id; a single skipped placeholder naming the missing directory when the data is
    absent, so that a missing data set shows up as a skip rather than as an empty test list."""
    paths = sorted(p for p in HEXDOM_DATA.glob(pattern)
                   if str(p.relative_to(HEXDOM_DATA)) not in exclude) if HEXDOM_DATA.is_dir() else []
    if not paths:
        where = HEXDOM_DATA if not HEXDOM_DATA.is_dir() else HEXDOM_DATA / pattern
        return [pytest.param(None, marks=pytest.mark.skip(reason=missing(where)), id="no-data")]
    return [pytest.param(p, id=str(p.relative_to(HEXDOM_DATA))) for p in paths]


def segmented_corpus_part(core, out, family, index, edge_weight=0.1):
    """Draw `index` (0-based) of a family of our own corpus (bench/make_corpus.py, default seed),
    made by FreeCAD in `out`, tessellated and segmented with `edge_weight`; the part must be square to
    the axes. Returns (labels, the default element size: the frame diagonal / 30). Skips when
    _hexdom has no OpenCASCADE (the part is a STEP file)."""
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    script = REPO / "bench" / "make_corpus.py"
    p = subprocess.run([sys.executable, str(script), str(out), "--families", family, "--count", str(index + 1), "--no-fixed"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    V, F, face = core.tessellate_file(str(Path(out) / f"{family}_{index:03d}.step"))
    surface = core.Surface(V, F, face)
    assert not core.cube_frame(surface)["turned"]  # square to the axes: no frame to pass
    size = core.frame_diagonal(surface, [[1, 0, 0], [0, 1, 0], [0, 0, 1]]) / 30.0
    return core.segment(surface, edge_weight=edge_weight), size


def hexdom_bin():
    """The hexdom program of the build under test; a missing build fails (it is not a skip)."""
    if not HEXDOM_BIN.is_file():
        pytest.fail(f"{HEXDOM_BIN} not found: build first (make build) or set HEXDOM_BUILD_DIR")
    return HEXDOM_BIN


def load_core():
    """HexDomWorkbench.core, checked to run the _hexdom module of BUILD_DIR: core.py falls back to
    other locations (an installed copy, ./build) when that one is missing or fails to import, and
    the tests would then silently test another build."""
    from HexDomWorkbench import core
    loaded = Path(core._hexdom.__file__).resolve()
    if BUILD_DIR not in loaded.parents:
        pytest.fail(f"_hexdom was loaded from {loaded}, not from {BUILD_DIR / 'python'} "
                    f"(is the module built there, and does it import?)")
    return core
