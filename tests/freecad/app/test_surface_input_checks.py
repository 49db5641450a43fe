"""A triangle file read into a HexDom Surface is checked as every meshing path checks its input
(issue "Surfaces as other tools export them"): an inside-out box is turned around with a warning
(the Surface encloses a positive volume, the same as the box's), two overlapping boxes written as
one surface are refused naming two crossing triangles, the Surface marked in error. The volumes are
computed here from the triangles FreeCAD holds (numpy), not by the core."""

import numpy as np
import pytest

import FreeCAD

from HexDomWorkbench import api, make
from HexDomWorkbench.objects import tessellation

import fc_testdata

_box, _write_stl = fc_testdata.box_triangles, fc_testdata.write_stl


def _volume(obj):
    s = tessellation.get_surface(obj)
    a, b, c = (s.V[s.F[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def test_an_inside_out_file_is_turned_around_with_a_warning(doc, tmp_path):
    path = _write_stl(tmp_path / "inside_out.stl", _box((0, 0, 0), (10, 10, 10), reverse=True))
    obj = make.make_surface(doc, path=path)
    api.recompute_document(doc, [obj])
    assert "Invalid" not in obj.State and obj.TriangleCount == 12
    assert _volume(obj) == pytest.approx(1000.0)


def test_a_self_crossing_file_is_refused_naming_two_triangles(doc, tmp_path):
    path = _write_stl(tmp_path / "soup.stl", _box((0, 0, 0), (10, 10, 10))
                      + _box((5, 5, 5), (15, 15, 15)))
    obj = make.make_surface(doc, path=path)
    with pytest.raises(api.RecomputeError, match="soup.stl crosses itself: triangles"):
        api.recompute_document(doc, [obj])
    assert "Invalid" in obj.State or "Error" in obj.State
    FreeCAD.Console.PrintMessage("soup.stl: {}\n".format(obj.getStatusString()))
