"""The hexdom program on bad input and bad usage.

Malformed files (made here) must give exit code 1 and exactly one line on stderr,
`hexdom: error: <path>:<line>: <text>`, naming the file and the offending line, and must leave no
output file (and no temporary file) behind. Usage errors exit 2; --help and --version exit 0.
"""

import re
import struct
import subprocess

import pytest

HEX_NODES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]


def k_file(nodes=None, solid="       1       1       1       2       3       4       5       6       7       8",
           end=True):
    """A one-hex LS-DYNA file: line 1 *KEYWORD, 2 *ELEMENT_SOLID, 3 the hex, 4 *NODE, 5.. nodes."""
    nodes = nodes if nodes is not None else [f"{i + 1},{x},{y},{z}" for i, (x, y, z) in enumerate(HEX_NODES)]
    text = "*KEYWORD\n*ELEMENT_SOLID\n" + solid + "\n*NODE\n" + "\n".join(nodes) + "\n"
    return text + ("*END\n" if end else "")


def vtk_file(points=None, cells="8 0 1 2 3 4 5 6 7", types="12", version="4.2", mode="ASCII",
             dataset="UNSTRUCTURED_GRID"):
    """A one-hex legacy VTK file: lines 1-4 header, 5 POINTS, 6-13 points, 14 CELLS, 15 the cell,
    16 CELL_TYPES, 17 the type."""
    points = points if points is not None else [f"{x} {y} {z}" for x, y, z in HEX_NODES]
    ncell = len(cells.split())
    return (f"# vtk DataFile Version {version}\nmalformed test\n{mode}\nDATASET {dataset}\n"
            f"POINTS {len(points)} double\n" + "\n".join(points) + "\n"
            f"CELLS 1 {ncell}\n{cells}\nCELL_TYPES 1\n{types}\n")


def binary_vtk(points=HEX_NODES, cell=(8, 0, 1, 2, 3, 4, 5, 6, 7), cut=None):
    """Binary (big-endian) one-hex VTK: header lines 1-5, point bytes from line 6, then
    CELLS on line 7 with its bytes from line 8, CELL_TYPES on line 9 with bytes from line 10."""
    data = b"# vtk DataFile Version 4.2\nbinary test\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
    data += f"POINTS {len(points)} double\n".encode()
    data += b"".join(struct.pack(">3d", *p) for p in points) + b"\n"
    data += f"CELLS 1 {len(cell)}\n".encode() + struct.pack(f">{len(cell)}i", *cell) + b"\n"
    data += b"CELL_TYPES 1\n" + struct.pack(">i", 12) + b"\n"
    return data[:cut] if cut else data


GOOD_K = k_file()
GOOD_VTK = vtk_file()
_points_cut = GOOD_VTK.index("1 1 0\n") + 3  # inside POINTS, in the middle of line 8
_cells_cut = GOOD_VTK.index("4 5 6 7")   # inside the cell list, on line 15
_pt = [f"{x} {y} {z}" for x, y, z in HEX_NODES]

# (id, file name, content, expected line, expected text)
MALFORMED = [
    ("k-truncated-in-nodes", "cut.k", k_file(end=False)[:k_file(end=False).index("6,1,0,1")], 3,
     "refers to node 6"),
    ("k-truncated-element", "cutelem.k", "*KEYWORD\n*ELEMENT_SOLID\n       1       1       1       2", 3,
     "expects 10 fields"),
    ("k-missing-node", "missing.k", k_file(solid="1,1,1,2,3,4,5,6,7,9"), 3, "node 9"),
    ("k-nan-coordinate", "nan.k", k_file(nodes=[f"{i + 1},{x},{y},{z}" if i != 6 else "7,1,nan,1"
                                               for i, (x, y, z) in enumerate(HEX_NODES)]), 11,
     "not a finite number"),
    ("k-inf-coordinate", "inf.k", k_file(nodes=[f"{i + 1},{x},{y},{z}" if i != 0 else "1,-inf,0,0"
                                               for i, (x, y, z) in enumerate(HEX_NODES)]), 5,
     "not a finite number"),
    ("k-unknown-keyword", "keyword.k", k_file().replace("*NODE", "*NODES"), 4, "unknown keyword *NODES"),
    ("k-wrong-keyword", "wrongkw.k", k_file().replace("*NODE", "*ELEMENT_SHELL"), 5,
     "*ELEMENT_SHELL expects at least 5 fields"),
    ("k-duplicate-node", "dup.k", k_file(nodes=[f"{i + 1},{x},{y},{z}" for i, (x, y, z) in enumerate(HEX_NODES)]
                                          + ["3,5,5,5"]), 13, "node id 3 is defined twice"),
    ("k-pyramid", "pyramid.k", k_file(solid="1,1,1,2,3,4,5,5,5,5"), 3, "neither a hex"),
    ("k-data-before-keyword", "nokw.k", "1,0,0,0\n" + GOOD_K, 1, "not an LS-DYNA keyword file"),
    ("k-garbage", "garbage.k", b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4, 1, "not an LS-DYNA keyword file"),
    ("k-id-out-of-range", "bigid.k", k_file(nodes=[f"{i + 1},{x},{y},{z}" for i, (x, y, z) in enumerate(HEX_NODES)]
                                             + ["99999999999,0,0,0"]), 13, "not a 32-bit integer"),
    ("k-shell-repeats-node", "shell.k", "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n*ELEMENT_SHELL\n"
                                        "1,1,1,2,1,3\n*END\n", 7, "repeats node"),
    ("vtk-truncated-points", "cutpoints.vtk", GOOD_VTK[:_points_cut], 8, "truncated"),
    ("vtk-truncated-cells", "cutcells.vtk", GOOD_VTK[:_cells_cut], 15, "truncated"),
    ("vtk-missing-point", "missing.vtk", vtk_file(cells="8 0 1 2 3 4 5 6 8"), 15, "refers to point 8"),
    ("vtk-nan-point", "nan.vtk", vtk_file(points=_pt[:3] + ["1 nan 0"] + _pt[4:]), 9, "not a finite number"),
    ("vtk-unknown-cell-type", "type.vtk", vtk_file(types="14"), 17, "unsupported VTK cell type 14"),
    ("vtk-wrong-node-count", "count.vtk", vtk_file(cells="4 0 1 2 3"), 15, "has 4 nodes, expected 8"),
    ("vtk-pyramid-as-hex", "pyr.vtk", vtk_file(cells="8 0 1 2 3 4 4 4 4"), 15, "neither a hexahedron"),
    ("vtk-fractional-index", "frac.vtk", vtk_file(cells="8 0 1 2 3 4 5 6.5 7"), 15, "not a valid integer"),
    ("vtk-not-vtk", "text.vtk", "hello\nworld\n", 1, "not a legacy VTK file"),
    ("vtk-bad-mode", "mode.vtk", vtk_file(mode="ASCIX"), 3, "ASCII or BINARY"),
    ("vtk-other-dataset", "dataset.vtk", vtk_file(dataset="STRUCTURED_POINTS"), 4, "UNSTRUCTURED_GRID"),
    ("vtk-unknown-section", "section.vtk", GOOD_VTK + "FROBNICATE 3\n", 18, "unknown section"),
    ("vtk-corrupt-count", "bigcount.vtk", GOOD_VTK.replace("POINTS 8", "POINTS 800000000000"), 5,
     "larger than the file"),
    ("vtk-bad-offsets", "offsets.vtk",
     "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n"
     "0 1 0\n0 0 1\nCELLS 2 4\nOFFSETS vtktypeint64\n2 6\nCONNECTIVITY vtktypeint64\n0 1 2 3\n"
     "CELL_TYPES 1\n10\n", 12, "OFFSETS"),
    ("vtk-binary-truncated", "cutbin.vtk", binary_vtk(cut=150), 6, "truncated"),
    ("vtk-binary-nan", "nanbin.vtk", binary_vtk(points=HEX_NODES[:5] + [(1, float("nan"), 1)] + HEX_NODES[6:]),
     6, "not finite"),
    ("vtk-binary-bad-index", "idxbin.vtk", binary_vtk(cell=(8, 0, 1, 2, 3, 4, 5, 6, 99)), 8,
     "refers to point 99"),
    ("stl-garbage", "garbage.stl", b"\x00\x01garbage that is neither binary nor ascii stl\n" * 3, 1,
     "not an STL file"),
    ("stl-truncated", "cut.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", 5,
     "truncated"),
    ("stl-bad-number", "num.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n"
                                  "vertex 0 1 0\nendloop\nendfacet\nendsolid\n", 5, "not a finite number"),
    ("obj-missing-vertex", "missing.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 4, "refers to vertex 9"),
    ("obj-bad-coordinate", "coord.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", 2, "not a finite number"),
]


def run(hexdom_bin, *args, cwd=None):
    return subprocess.run([str(hexdom_bin), *map(str, args)], capture_output=True, text=True, cwd=cwd,
                          timeout=60)


def error_line(result):
    lines = result.stderr.splitlines()
    assert len(lines) == 1, f"expected one line on stderr, got:\n{result.stderr}"
    assert lines[0].startswith("hexdom: error: "), lines[0]
    return lines[0]


@pytest.fixture
def dirs(tmp_path):
    (tmp_path / "in").mkdir()
    (tmp_path / "out").mkdir()
    return tmp_path / "in", tmp_path / "out"


def test_good_files_convert(hexdom_bin, dirs):
    """Positive control: the well-formed versions of the files below convert."""
    src, out = dirs
    for name, content in (("good.k", GOOD_K), ("good.vtk", GOOD_VTK), ("good-binary.vtk", binary_vtk())):
        path = src / name
        path.write_bytes(content.encode() if isinstance(content, str) else content)
        r = run(hexdom_bin, "convert", "-i", path, "-o", out / (name + ".k"))
        assert r.returncode == 0, r.stderr
        assert "1 hex" in r.stderr and (out / (name + ".k")).is_file()


@pytest.mark.parametrize("case", MALFORMED, ids=[c[0] for c in MALFORMED])
def test_malformed_input_is_reported_with_file_and_line(hexdom_bin, dirs, case):
    _, name, content, line, text = case
    src, out = dirs
    path = src / name
    path.write_bytes(content.encode() if isinstance(content, str) else content)
    target = out / ("result.k" if name.endswith(".vtk") else "result.vtk")
    r = run(hexdom_bin, "convert", "-i", path, "-o", target)
    assert r.returncode == 1, r.stderr
    msg = error_line(r)
    assert re.match(rf"hexdom: error: {re.escape(str(path))}:{line}: .+", msg), msg
    assert text in msg, msg
    assert list(out.iterdir()) == [], "a failed conversion must leave no output (nor temporary) file"
    # `hexdom quality` reads the same way.
    q = run(hexdom_bin, "quality", "-i", path, "--json")
    assert q.returncode == 1 and error_line(q) == msg and q.stdout == ""


def test_empty_file_is_an_input_error(hexdom_bin, dirs):
    src, out = dirs
    for name in ("empty.k", "empty.vtk", "empty.stl", "empty.obj"):
        (src / name).write_bytes(b"")
        r = run(hexdom_bin, "convert", "-i", src / name, "-o", out / "x.vtk")
        assert r.returncode == 1 and str(src / name) in error_line(r)
    assert list(out.iterdir()) == []


def test_missing_input_file(hexdom_bin, dirs):
    src, out = dirs
    r = run(hexdom_bin, "convert", "-i", src / "nope.k", "-o", out / "x.vtk")
    assert r.returncode == 1 and "nope.k" in error_line(r) and "cannot open" in r.stderr
    assert list(out.iterdir()) == []


def test_failed_conversion_keeps_existing_output(hexdom_bin, dirs):
    src, out = dirs
    (src / "bad.k").write_text(k_file(solid="1,1,1,2,3,4,5,6,7,9"))
    (out / "result.vtk").write_text("previous result\n")
    r = run(hexdom_bin, "convert", "-i", src / "bad.k", "-o", out / "result.vtk")
    assert r.returncode == 1
    assert (out / "result.vtk").read_text() == "previous result\n"
    assert [p.name for p in out.iterdir()] == ["result.vtk"]


@pytest.mark.parametrize("target", ["result.xyz", "result", "result.vtk.bak", "missing_dir/result.vtk",
                                    "result.stl", "result.obj"])
def test_unwritable_output_is_an_error_and_leaves_nothing(hexdom_bin, dirs, target):
    """Unknown extension, no extension, a missing directory, a volume mesh into a surface format."""
    src, out = dirs
    (src / "good.k").write_text(GOOD_K)
    r = run(hexdom_bin, "convert", "-i", src / "good.k", "-o", out / target)
    assert r.returncode == 1, r.stderr
    msg = error_line(r)
    assert str(out / target) in msg, msg
    if "." not in target or target.endswith((".xyz", ".bak")):
        assert "unknown file format" in msg
    assert list(out.iterdir()) == []


def test_unknown_input_extension(hexdom_bin, dirs):
    src, out = dirs
    (src / "mesh.unv").write_text(GOOD_K)
    r = run(hexdom_bin, "convert", "-i", src / "mesh.unv", "-o", out / "x.vtk")
    assert r.returncode == 1 and "mesh.unv" in error_line(r) and "unknown file format" in r.stderr
    assert list(out.iterdir()) == []


USAGE = [
    [],
    ["frobnicate"],
    ["convert"],
    ["convert", "-i", "{src}"],
    ["convert", "-o", "{out}"],
    ["convert", "-i", "{src}", "-o", "{out}", "--frobnicate"],
    ["convert", "-i", "{src}", "-o"],
    ["quality"],
    ["quality", "-i"],
    ["quality", "-i", "{src}", "extra"],
]


@pytest.mark.parametrize("args", USAGE, ids=[" ".join(a) or "no-arguments" for a in USAGE])
def test_usage_errors_exit_2(hexdom_bin, dirs, args):
    src, out = dirs
    (src / "good.k").write_text(GOOD_K)
    argv = [a.format(src=src / "good.k", out=out / "x.vtk") for a in args]
    r = run(hexdom_bin, *argv)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stderr.strip() != "" and "Traceback" not in r.stderr
    assert list(out.iterdir()) == []


@pytest.mark.parametrize("args", [["--help"], ["-h"], ["convert", "--help"], ["quality", "--help"]])
def test_help_exits_0(hexdom_bin, args):
    r = run(hexdom_bin, *args)
    assert r.returncode == 0, r.stderr
    text = r.stdout
    if args[0] == "convert":
        assert "--input" in text and "--output" in text and "--binary" in text
    elif args[0] == "quality":
        assert "--json" in text
    else:
        assert "convert" in text and "quality" in text


def test_version_exits_0(hexdom_bin):
    r = run(hexdom_bin, "--version")
    assert r.returncode == 0
    assert re.fullmatch(r"hexdom \d+\.\d+\.\d+\s*", r.stdout), r.stdout
