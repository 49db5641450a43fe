"""What the Edit Patches and Build Polycube panels do, driven without FreeCAD or Qt: the
PatchEditor and PolycubeBuilder (HexDomWorkbench.logic) the panels' widgets call. They moved
here from tests/freecad/app/test_dialog_logic.py with the code (taskpanels/ -> logic/); what
needs a FreeCAD document (patch edits stored on a Segmentation, a box made in Part) stayed there."""

import os
import subprocess
import sys

import numpy as np
import pytest

import hexdom_test_support as support

try:
    core = support.load_core()
except ImportError as e:
    pytest.skip(str(e), allow_module_level=True)

from HexDomWorkbench.logic import cells, labels, patch_editing, polycube_building  # noqa: E402
from HexDomWorkbench.logic.patch_editing import PatchEditor  # noqa: E402
from HexDomWorkbench.logic.polycube_building import PolycubeBuilder, order_block  # noqa: E402

EXAMPLES = support.REPO / "examples" / "data"
PATCHES = str(EXAMPLES / "lbracket_patches.k")
STRUCTURE = str(EXAMPLES / "lbracket_structure.k")
ROCKERARM = support.HEXDOM_DATA / "rockerarm"
ROCKERARM_PATCHES = str(ROCKERARM / "rockerarm_indexPatch_hexdom.k")
ROCKERARM_STRUCTURE = str(ROCKERARM / "rockerarm_polycube_withtet.k")


def bracket_editor():
    s = core.read_surface(PATCHES)
    return s, PatchEditor(s.V, s.F, s.patch)


def boundary_vertices(editor, patch_id, other):
    """Vertices on the curve between ``patch_id`` and ``other`` (not at its ends)."""
    out = []
    for v in np.unique(editor.F[editor.patches == patch_id]).tolist():
        ids = set(editor.patches[editor.vertex_triangles(v)].tolist())
        if ids == {patch_id, other}:
            out.append(v)
    return out


def test_panel_logic_needs_neither_freecad_nor_qt():
    import HexDomWorkbench
    root = os.path.dirname(os.path.dirname(HexDomWorkbench.__file__))
    code = ("import sys; sys.path.insert(0, {!r}); "
            "import HexDomWorkbench.logic.patch_editing, "
            "HexDomWorkbench.logic.polycube_building; "
            "print(sorted(m for m in ('FreeCAD', 'FreeCADGui', 'PySide', 'PySide2', 'pivy') "
            "if m in sys.modules))".format(root))
    env = dict(os.environ)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


# ------------------------------------------------------------------------------------------------
# Edit Patches


def test_planted_island_is_listed_and_fixed_by_reassigning_it():
    s, e = bracket_editor()
    assert e.problems() == [] and not e.is_modified()
    planted = support.island(e)
    assert 4 <= len(planted) <= 16
    assert e.select_facets(planted, "replace") == len(planted)
    new_id = e.new_patch()
    assert new_id == 18 and e.patch_label(new_id) == e.patch_label(5)
    kinds = sorted(p.kind for p in e.problems())
    assert kinds == ["curve_count", "not_disk", "two_patch_corner"]
    curve = next(p for p in e.problems() if p.kind == "curve_count")
    np.testing.assert_array_equal(e.problem_triangles(curve), np.sort(planted))
    assert e.patch_of_number(curve.patches[0]) == new_id
    e.select_facets(e.problem_triangles(curve), "replace")
    assert e.suggested_patch() == 5
    e.assign_to_patch(5)
    assert e.problems() == [] and not e.is_modified()
    assert e.undo() and len(e.problems()) == 3
    assert e.redo() and e.problems() == []
    assert not e.redo()


def test_orientation_sends_an_island_back_to_its_neighbour():
    _, e = bracket_editor()
    planted = support.island(e)
    e.select_facets(planted, "replace")
    e.new_patch(label="-Z")
    assert e.patch_label(18) == 6 and len(e.problems()) == 3
    e.select_facets(planted, "replace")
    assert e.assign_orientation(patch_editing.LABEL_NAMES[e.patch_label(5)]) == [5]
    assert e.problems() == [] and not e.is_modified()


def test_split_puts_corners_on_the_neighbours_and_merge_takes_them_back():
    _, e = bracket_editor()
    # Patch 5 is a quad; cut it from the middle of one side to the middle of the opposite side.
    neighbours = {int(p) for t in np.flatnonzero(e.patches == 5).tolist()
                  for v in e.F[t] for p in e.patches[e.vertex_triangles(v)].tolist()} - {5}
    sides = [(n, boundary_vertices(e, 5, n)) for n in sorted(neighbours)]
    sides = [(n, vs) for n, vs in sides if len(vs) >= 3]
    best = None
    for i in range(len(sides)):
        for j in range(i + 1, len(sides)):
            a = sides[i][1][len(sides[i][1]) // 2]
            b = sides[j][1][len(sides[j][1]) // 2]
            d = np.linalg.norm(e.V[a] - e.V[b])
            if best is None or d > best[0]:
                best = (d, a, b)
    _, a, b = best
    e.add_path_vertex(a)
    e.add_path_vertex(b)
    assert e.path_patch() == 5
    new_ids = e.split()
    assert new_ids == [18] and len(e.patch_ids()) == 18 and e.path == []
    # Both halves are quads, but each neighbour across the cut now has a fifth curve.
    problems = e.problems()
    assert [p.kind for p in problems] == ["curve_count", "curve_count"]
    assert {e.patch_of_number(p.patches[0]) for p in problems}.isdisjoint({5, 18})
    e.select_facets(np.flatnonzero(e.patches == 5)[:1], "replace")
    e.select_facets(np.flatnonzero(e.patches == 18)[:1], "add")
    assert e.merge() == 5 and len(e.patch_ids()) == 17
    assert e.problems() == [] and not e.is_modified()


def test_merging_two_patches_breaks_the_corner_condition_until_undone():
    _, e = bracket_editor()
    e.merge(1, 2)
    assert any(p.kind == "two_patch_corner" for p in e.problems())
    e.undo()
    assert e.problems() == []


def test_selection_modes_faces_and_errors():
    s, e = bracket_editor()
    assert e.select_facets([0, 1, 2], "replace") == 3
    assert e.select_facets([1], "toggle") == 2 and e.select_facets([1], "toggle") == 3
    assert e.select_facets([0], "remove") == 2
    assert e.select_patch(3, "replace") == int(np.count_nonzero(s.patch == 3))
    assert e.selected_patches() == [3]
    with pytest.raises(ValueError, match="no CAD face ids"):
        e.select_face(1)
    e2 = PatchEditor(s.V, s.F, s.patch, face_ids=s.patch)
    assert e2.select_face(4) == int(np.count_nonzero(s.patch == 4))
    with pytest.raises(ValueError, match="no patch 99"):
        e.assign_to_patch(99)
    e.clear_selection()
    with pytest.raises(ValueError, match="no facets selected"):
        e.new_patch()
    with pytest.raises(ValueError, match="two or more patches"):
        e.merge()
    with pytest.raises(ValueError, match="not one of"):
        e.assign_orientation("+W")
    with pytest.raises(core.GeometryError):
        e.merge(1, 17)  # the ramp and the far end share no edge


def test_lasso_polygon_test_against_winding_angles():
    """points_in_polygon (even-odd crossings) against the total angle a polygon turns about each
    point, on a star and on a polygon with a notch; points near an edge are left out."""
    rng = np.random.default_rng(5)
    t = np.linspace(0, 2 * np.pi, 14, endpoint=False)
    star = np.c_[np.cos(t), np.sin(t)] * np.where(np.arange(14) % 2 == 0, 10.0, 4.0)[:, None]
    notch = np.array([[0, 0], [10, 0], [10, 10], [6, 10], [6, 3], [4, 3], [4, 10], [0, 10]],
                     float)
    for polygon in (star, notch):
        pts = rng.uniform(polygon.min(axis=0) - 1, polygon.max(axis=0) + 1, (4000, 2))
        d = polygon[None, :, :] - pts[:, None, :]
        e = np.roll(d, -1, axis=1)
        turn = np.arctan2(d[..., 0] * e[..., 1] - d[..., 1] * e[..., 0],
                          (d * e).sum(axis=2)).sum(axis=1)
        expected = np.abs(turn) > np.pi
        a, b = polygon, np.roll(polygon, -1, axis=0)
        ab = b - a
        u = np.clip(np.einsum("pqk,qk->pq", pts[:, None, :] - a[None], ab)
                    / np.einsum("qk,qk->q", ab, ab), 0, 1)
        far = np.linalg.norm(pts[:, None, :] - (a[None] + u[..., None] * ab[None]),
                             axis=2).min(axis=1) > 1e-6
        got = patch_editing.points_in_polygon(pts, polygon)
        assert 500 < expected.sum() < 3500
        np.testing.assert_array_equal(got[far], expected[far])
    assert not patch_editing.points_in_polygon([[0, 0]], [[0, 0], [1, 1]]).any()


def test_opposite_orientations_touching_are_listed_highlighted_and_cut_apart():
    """A thin wedge (its long sides' normals 165 degrees apart, +Y and -Y, meet at the apex
    edge): the editor lists the opposite orientations touching, the problem's facets are the two
    sides, and a +X strip made at the apex separates them."""
    V, F, P = support.thin_wedge()
    e = PatchEditor(V, F, P)
    problems = e.problems()
    assert [p.kind for p in problems] == ["opposite_orientations"]
    assert sorted(e.problem_triangles(problems[0]).tolist()) == np.flatnonzero(
        np.isin(P, [1, 2])).tolist()
    apex = np.flatnonzero(np.isclose(V[:, 0], 10.0))
    strip = [t for t in range(len(F)) if P[t] in (1, 2) and np.isin(F[t], apex).any()]
    e.select_facets(strip, "replace")
    new = e.new_patch()
    assert patch_editing.LABEL_NAMES[e.patch_label(new)] == "+X"
    assert "opposite_orientations" not in [p.kind for p in e.problems()]


def test_changes_name_exactly_the_edited_triangles():
    _, e = bracket_editor()
    planted = support.island(e)
    e.select_facets(planted, "replace")
    e.new_patch(label=3)
    lt, ll, pt, pid = e.changes()
    np.testing.assert_array_equal(lt, np.sort(planted))
    assert set(ll.tolist()) == {3}
    np.testing.assert_array_equal(pt, np.sort(planted))
    assert set(pid.tolist()) == {18}


# ------------------------------------------------------------------------------------------------
# Build Polycube


def unit_cube():
    """The unit cube's corners in VTK hex order, and its hex block."""
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    return V, list(range(8))


def test_block_order_is_fixed_up_to_a_positive_block():
    V, hexa = unit_cube()
    rng = np.random.default_rng(3)
    for _ in range(5):
        shuffled = list(rng.permutation(hexa))
        t, ordered = order_block(V, shuffled)
        sj = polycube_building.scaled_jacobians(V, [ordered], t)
        assert t == core.HEX and sj[0] == pytest.approx(1.0)
    t, tet = order_block(V, [hexa[0], hexa[1], hexa[3], hexa[4]])
    assert t == core.TET and polycube_building.scaled_jacobians(V, [tet], t)[0] > 0.7
    t, wedge = order_block(V, [hexa[i] for i in (0, 1, 3, 4, 5, 7)])
    # Right isosceles triangles: Verdict gives sin(45 deg) * 2 / sqrt(3) = 0.816 at best.
    assert t == core.WEDGE and polycube_building.scaled_jacobians(V, [wedge], t)[0] > 0.8
    with pytest.raises(ValueError, match="8 \\(hex\\), 6 \\(prism\\) or 4 \\(tet\\)"):
        order_block(V, hexa[:5])
    flat = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], float)
    with pytest.raises(ValueError, match="no tet that is not inverted"):
        order_block(flat, [0, 1, 2, 3])


def test_bracket_structure_fills_its_patches_and_losing_a_block_shows():
    b = PolycubeBuilder(core.read_surface(PATCHES))
    assert b.corner_count == 18 and b.problems()[0].kind == "uncovered_patch"
    assert len(b.problems()) == 17
    assert b.import_structure(STRUCTURE) == 0
    assert b.counts() == {"hex": 3, "prism": 1, "tet": 0} and b.problems() == []
    b.delete_block(3)
    kinds = sorted({p.kind for p in b.problems()})
    assert kinds == ["open_face", "uncovered_patch"]
    assert b.undo() and b.problems() == []


def test_rebuilding_the_bracket_block_by_block_from_shuffled_picks():
    s = core.read_surface(PATCHES)
    reference = PolycubeBuilder(s)
    reference.import_structure(STRUCTURE)
    b = PolycubeBuilder(s)
    rng = np.random.default_rng(7)
    for t, verts in reference.blocks:
        b.select_vertices(list(rng.permutation(verts)), "replace")
        b.add_block()
    assert b.counts() == reference.counts() and b.problems() == []
    mesh = core.improve(core.generate(s, b.structure(), level=2), s)
    assert core.quality_report(mesh)["hex"]["inverted"] == 0


def test_inverted_overlapping_and_shared_faces_are_listed():
    V, hexa = unit_cube()
    b = PolycubeBuilder(structure=core.Mesh(V, np.array([hexa], np.int32),
                                            np.array([core.HEX], np.int32),
                                            np.ones(1, np.int32)))
    assert [p.kind for p in b.problems()] == ["no_boundary"]
    b.blocks = [(core.HEX, tuple(hexa[4:] + hexa[:4]))]  # top and bottom swapped
    b._problems = None
    assert "inverted" in [p.kind for p in b.problems()]
    b.blocks = [(core.HEX, tuple(hexa))]
    shifted = [b.add_vertex(b.points[v] + (0.5, 0.0, 0.0)) for v in hexa]
    b.add_block(shifted)
    overlap = [p for p in b.problems() if p.kind == "overlap"]
    assert len(overlap) == 1 and overlap[0].blocks == [0, 1]
    b.undo()
    assert [p.kind for p in b.problems()] == ["no_boundary"] + ["unused_vertex"] * 8


def two_hexes(shift):
    """A builder with the unit cube and a second unit cube moved by ``shift`` (own vertices)."""
    V, hexa = unit_cube()
    b = PolycubeBuilder(structure=core.Mesh(V, np.array([hexa], np.int32),
                                            np.array([core.HEX], np.int32),
                                            np.ones(1, np.int32)))
    moved = [b.add_vertex(b.points[v] + np.asarray(shift, float)) for v in hexa]
    b.add_block(moved)
    return b


@pytest.mark.parametrize("shift", [(0.9, 0.1, 0.1), (0.8, 0.8, 0.8), (-0.85, 0.3, -0.2)])
def test_a_block_poking_into_another_without_sharing_a_face_is_flagged(shift):
    b = two_hexes(shift)
    assert not set(b.blocks[0][1]) & set(b.blocks[1][1])
    # The poke is shallow: neither cube's centre nor the points half-way from it to its corners
    # (what a centroid test samples) lies in the other cube (axis-aligned: a box test).
    for a, o in ((0, 1), (1, 0)):
        pts = b.points[list(b.blocks[o][1])]
        centre = pts.mean(axis=0)
        samples = np.vstack([centre, 0.5 * (pts + centre)])
        lo = b.points[list(b.blocks[a][1])].min(axis=0)
        hi = b.points[list(b.blocks[a][1])].max(axis=0)
        assert not np.any(np.all((samples > lo) & (samples < hi), axis=1))
    overlap = [p for p in b.problems() if p.kind == "overlap"]
    assert len(overlap) == 1 and overlap[0].blocks == [0, 1]
    assert set(overlap[0].vertices) == set(b.blocks[0][1]) | set(b.blocks[1][1])


@pytest.mark.parametrize("shift", [(1.0, 0.0, 0.0), (1.0, 0.5, 0.0), (1.0, 1.0, 1.0),
                                   (0.0, 0.0, -1.0)])
def test_blocks_that_only_touch_do_not_overlap(shift):
    assert [p.kind for p in two_hexes(shift).problems()] == ["no_boundary"]


def test_inside_block_agrees_with_the_block_map():
    """Points made by each block's own map from parameters inside / outside its domain are
    found inside / outside, on a warped hex, a prism and a tet (the tet against a barycentric
    solve)."""
    rng = np.random.default_rng(11)
    V, hexa = unit_cube()
    warped = V[hexa] + rng.uniform(-0.12, 0.12, (8, 3))
    params = rng.uniform(0.03, 0.97, (300, 3))
    N, _ = polycube_building._shape(core.HEX, params)
    assert polycube_building.inside_block(core.HEX, warped, N @ warped).all()
    outside = params.copy()
    outside[:, 0] = rng.choice([-0.3, 1.3], 300) + rng.uniform(-0.1, 0.1, 300)
    N, _ = polycube_building._shape(core.HEX, outside)
    assert not polycube_building.inside_block(core.HEX, warped, N @ warped).any()
    prism = V[[hexa[i] for i in (0, 1, 3, 4, 5, 7)]]
    tri = rng.dirichlet([1, 1, 1], 200) * 0.94 + 0.02
    pts = np.hstack([tri[:, 1:], rng.uniform(0.03, 0.97, (200, 1))])
    N, _ = polycube_building._shape(core.WEDGE, pts)
    assert polycube_building.inside_block(core.WEDGE, prism, N @ prism).all()
    tet = np.array([[0, 0, 0], [2, 0.1, 0], [0.3, 1.5, 0.2], [0.1, 0.4, 1.7]])
    queries = rng.uniform(-0.5, 2.0, (500, 3))
    bary = np.linalg.solve(np.c_[tet, np.ones(4)].T, np.c_[queries, np.ones(500)].T).T
    expected = np.all(bary > 1e-3, axis=1)
    assert 20 < expected.sum() < 480
    np.testing.assert_array_equal(polycube_building.inside_block(core.TET, tet, queries),
                                  expected)


def test_patches_covered_twice_and_faces_in_three_blocks_are_listed():
    """The bracket's structure with block 1 twice: its patches are covered twice, its face
    inside the bracket is in three blocks, and the copy overlaps it; add_block refuses a copy."""
    b = PolycubeBuilder(core.read_surface(PATCHES))
    b.import_structure(STRUCTURE)
    with pytest.raises(ValueError, match="block 1 already uses these vertices"):
        b.add_block(list(b.blocks[0][1]))
    shared = [f for f in polycube_building.block_faces(*b.blocks[0])
              if polycube_building.face_key(f) not in b.patch_faces]
    b.blocks = b.blocks + [b.blocks[0]]
    b._problems = None
    problems = b.problems()
    kinds = sorted({p.kind for p in problems})
    assert kinds == ["duplicate_block", "face_shared", "overlap", "patch_covered_twice"]
    twice = [p for p in problems if p.kind == "patch_covered_twice"]
    on_patches = [f for f in polycube_building.block_faces(*b.blocks[0])
                  if polycube_building.face_key(f) in b.patch_faces]
    assert len(twice) == len(on_patches) and all(p.blocks == [0, 4] for p in twice)
    in_three = [p for p in problems if p.kind == "face_shared"]
    assert len(in_three) == len(shared) and all(sorted(p.blocks)[0] == 0 and 4 in p.blocks
                                                and len(p.blocks) == 3 for p in in_three)
    assert [p.blocks for p in problems if p.kind == "overlap"] == [[0, 4]]


def test_the_core_matcher_names_each_problem():
    """core.match_faces_to_patches on one hex: its six faces are the six patches; a patch
    dropped leaves an open face, a patch on no face and two patches with one set of corners
    are listed, each naming its patches and faces."""
    faces = [(0, list(f)) for f in polycube_building.block_faces(core.HEX, list(range(8)))]
    patches = [sorted(f) for _, f in faces]
    problems, face_of_patch, patch_of_face = core.match_faces_to_patches(faces, patches)
    assert problems == [] and sorted(face_of_patch) == list(range(6))
    assert [patch_of_face[face_of_patch[p]] for p in range(6)] == list(range(6))
    problems, _, _ = core.match_faces_to_patches(faces, patches[1:] + [[0, 1, 8, 9]])
    assert [p["kind"] for p in problems] == ["face_on_no_patch", "patch_on_no_face"]
    assert problems[0]["faces"] == [0] and problems[1]["patches"] == [5]
    assert "matches no patch" in problems[0]["message"]
    problems, _, _ = core.match_faces_to_patches(faces, patches + [patches[2][::-1]])
    assert [(p["kind"], p["patches"]) for p in problems] == [("patches_share_corners", [2, 6])]


def test_patches_with_the_same_corners_are_a_problem():
    b = PolycubeBuilder(core.read_surface(PATCHES))
    b.import_structure(STRUCTURE)
    twin = dict(b.boundary.faces[3], patch=99)
    b.boundary.faces.append(twin)
    b._problems = None
    problems = b.problems()
    assert [p.kind for p in problems] == ["patches_share_corners"]
    assert problems[0].patches == [b.boundary.faces[3]["patch"], 99]
    assert "have the same corners" in problems[0].message


def test_interior_vertices_added_moved_deleted():
    b = PolycubeBuilder(core.read_surface(PATCHES))
    c = b.add_vertex_at_centroid([0, 1, 2])
    assert c == 18 and not b.is_corner(c)
    np.testing.assert_allclose(b.points[c], b.points[[0, 1, 2]].mean(axis=0))
    assert b.problems()[-1].kind == "unused_vertex"
    b.move_vertex(c, (1.0, 2.0, 3.0))
    np.testing.assert_allclose(b.points[c], (1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="corner"):
        b.move_vertex(0, (0, 0, 0))
    with pytest.raises(ValueError, match="corner"):
        b.delete_vertex(0)
    b.delete_vertex(c)
    assert b.vertex_count == 18
    assert b.undo() and b.vertex_count == 19
    with pytest.raises(ValueError, match="pick the vertices"):
        b.add_vertex_at_centroid()


def test_structure_file_round_trip(tmp_path):
    b = PolycubeBuilder(core.read_surface(PATCHES))
    b.import_structure(STRUCTURE)
    out = str(tmp_path / "out.k")
    b.export_structure(out)
    again = PolycubeBuilder(core.read_surface(PATCHES))
    again.import_structure(out)
    assert again.blocks == b.blocks and again.problems() == []


@pytest.mark.skipif(not os.path.isfile(ROCKERARM_STRUCTURE),
                    reason="paper data missing: {}".format(ROCKERARM_STRUCTURE))
def test_rockerarm_structure_loads_with_no_problem():
    b = PolycubeBuilder(core.read_surface(ROCKERARM_PATCHES))
    assert b.corner_count == 141
    assert b.import_structure(ROCKERARM_STRUCTURE) == 12
    assert b.counts() == {"hex": 60, "prism": 11, "tet": 2}
    assert b.problems() == []


def test_labels_taken_from_normals_name_the_frames_axes():
    """The bracket's patches turned 45 degrees about Z, edited with the Segmentation's Frame: the
    labels the editor takes from normals (patches without labels, a new patch) are the square
    bracket's, not the model's axes' (which put the turned side faces between two labels)."""
    s, square = bracket_editor()
    t = np.radians(45.0)
    R = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    V = s.V @ R.T
    framed = PatchEditor(V, s.F, s.patch, frame=R.T)  # the frame undoes the turn
    assert np.array_equal(framed.labels, square.labels)
    plain = PatchEditor(V, s.F, s.patch)
    assert not np.array_equal(plain.labels, square.labels)
    planted = support.island(framed)
    assert framed.patch_label(framed.new_patch(planted)) == square.patch_label(5)
    assert np.array_equal(labels.labels_from_normals(V, s.F, s.patch, frame=R.T), square.labels)


def test_labels_taken_from_normals_follow_the_segmentation_s_stretch():
    """With the Segmentation's Stretch (a thin part segmented stretched), the editor's labels from
    normals and a new patch's label are those of the surface stretched so: the bracket stretched
    4 times along Z by the editor and by hand give the same labels, 128 triangles of its hole
    other than unstretched."""
    s, square = bracket_editor()
    f = np.array([1.0, 1.0, 4.0])
    stretched = PatchEditor(s.V, s.F, s.patch, stretch=f)
    by_hand = PatchEditor(s.V * f, s.F, s.patch)
    assert np.array_equal(stretched.labels, by_hand.labels)
    changed = stretched.labels != square.labels
    assert np.count_nonzero(changed) == 128
    tris = np.flatnonzero(s.patch == s.patch[np.flatnonzero(changed)[0]])
    new = stretched.patch_label(stretched.new_patch(tris))
    assert new == by_hand.patch_label(by_hand.new_patch(tris))
    assert new != square.patch_label(square.new_patch(tris))
    assert np.array_equal(labels.labels_from_normals(s.V, s.F, s.patch, stretch=f), by_hand.labels)


# ------------------------------------------------------------------------------------------------
# What the editors share: labels, the triangle adjacency, the block face table


def test_one_label_algebra_for_one_normal_and_for_rows():
    assert labels.LABEL_NAMES == core.LABEL_NAMES
    assert labels.nearest_label([0.3, -0.9, 0.2]).tolist() == [4]  # as the core's (axis_labels)
    rows = np.r_[labels.AXES, [[0.2, 0.1, -0.9]]]
    assert labels.nearest_label(rows).tolist() == [1, 2, 3, 4, 5, 6, 6]
    assert [labels.label_number(x) for x in ("+X", " -z ", 3)] == [1, 6, 3]
    for bad in ("X", 0, 7):
        with pytest.raises(ValueError):
            labels.label_number(bad)


def test_triangle_adjacency_pairs_triangles_across_their_edges():
    from HexDomWorkbench.logic import triangles
    # a square in two triangles, and a third triangle on the diagonal's far side of the square
    F = np.array([[0, 1, 2], [0, 2, 3], [2, 1, 4]])
    pairs = {tuple(sorted(p)) for p in triangles.triangle_adjacency(F).tolist()}
    assert pairs == {(0, 1), (0, 2)}
    assert triangles.connected_regions(F, [5, 5, 6]).tolist() == [0, 0, 1]
    edges, uses = triangles.edge_uses(F)
    assert len(edges) == 7 and sorted(uses.tolist()) == [1] * 5 + [2] * 2
    assert {tuple(e) for e in triangles.boundary_edges(F, [1, 1, 2]).tolist()} == {
        (0, 1), (0, 3), (2, 3), (1, 4), (2, 4), (1, 2)}
    assert triangles.all_edges(F).tolist() == sorted(map(list, edges.tolist()))


def test_the_block_face_table_is_the_cores_cell_types_and_closes_each_block():
    assert (cells.HEX, cells.WEDGE, cells.TET) == (core.HEX, core.WEDGE, core.TET)
    assert polycube_building.BLOCK_FACES is cells.BLOCK_FACES
    for t, n in cells.NODE_COUNT.items():
        assert n == core.NODE_COUNT[t]
        # every edge of a closed block is in two faces, once each way
        half = [(f[i], f[(i + 1) % len(f)]) for f in cells.BLOCK_FACES[t] for i in range(len(f))]
        assert sorted(half) == sorted((b, a) for a, b in half)
    V, hexa = unit_cube()
    faces, types, edges = cells.structure_boundary([hexa, [v + 4 for v in hexa]], [core.HEX] * 2)
    assert len(faces) == 10 and len(edges) == 20


def test_labels_from_normals_is_the_cores_and_matches_the_axis_nearest_each_normal():
    # One implementation (segmentation::labels_from_normals through _hexdom): checked here against
    # numpy's argmax over the six axes, per triangle and per patch, in a turned frame too.
    from HexDomWorkbench.logic import labels
    rng = np.random.default_rng(7)
    V = rng.normal(size=(60, 3))
    F = rng.integers(0, 60, size=(80, 3))
    F = F[(F[:, 0] != F[:, 1]) & (F[:, 1] != F[:, 2]) & (F[:, 0] != F[:, 2])]
    patch = rng.integers(1, 5, size=len(F)).astype(np.int32)
    axes = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    c = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    angle = 0.4
    R = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    for frame in (None, R):
        n = c if frame is None else c @ R.T
        expected = np.argmax(n @ axes.T, axis=1) + 1
        assert np.array_equal(labels.labels_from_normals(V, F, frame=frame), expected)
        mean = np.array([n[patch == p].sum(axis=0) for p in range(1, 5)])
        assert np.array_equal(labels.labels_from_normals(V, F, patch, frame=frame),
                              (np.argmax(mean @ axes.T, axis=1) + 1)[patch - 1])
    assert labels.nearest_label([[0, 0, -2], [0, 3, 0], [0, 0, 0]]).tolist() == [6, 3, 1]
    with pytest.raises(Exception, match="rotation"):
        labels.labels_from_normals(V, F, frame=np.eye(3) * 2)


def test_the_block_face_table_is_the_cores():
    # One face table: the workbench reads mesh::cell_faces through _hexdom; each face is outward,
    # so every hex face's normal points away from the unit cube's centre.
    from HexDomWorkbench import core
    assert cells.BLOCK_FACES[cells.HEX] == core.cell_faces(12) and len(cells.BLOCK_FACES[cells.HEX]) == 6
    cube = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    for face in cells.BLOCK_FACES[cells.HEX]:
        p = cube[list(face)]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        assert np.dot(n, p.mean(axis=0) - 0.5) > 0, face
    with pytest.raises(core.Error):
        core.cell_faces(9)
