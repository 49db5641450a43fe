"""View provider of HexDom Mesh: colours cells by type (hex / prism / tet) or by scaled Jacobian
through ViewProviderFemMesh.ElementColor (cell id -> colour; all faces of a cell share it)."""

import math

import FreeCAD

from .. import core
from ..convert import femmesh
from .view_base import VPBaseHexDomObject

COLOR_BY = ["Cell type", "Scaled Jacobian", "Plain"]

TYPE_COLORS = {
    core.HEX: (0.25, 0.52, 0.90),  # blue
    core.WEDGE: (1.00, 0.60, 0.10),  # orange
    core.TET: (0.80, 0.20, 0.80),  # magenta
    core.QUAD: (0.60, 0.60, 0.60),
    core.TRIANGLE: (0.60, 0.60, 0.60),
}
INVERTED_COLOR = (0.35, 0.0, 0.0)  # dark red: scaled Jacobian <= 0 or degenerate


def sj_color(sj):
    """Red (0) through yellow (0.5) to green (1); dark red for inverted or degenerate cells."""
    if sj is None or not math.isfinite(sj) or sj <= 0.0 or sj > 1.0 + 1e-9:
        return INVERTED_COLOR
    t = min(sj, 1.0)
    if t < 0.5:
        return (1.0, 2.0 * t, 0.0)
    return (2.0 * (1.0 - t), 1.0, 0.0)


def cell_colors(mesh, color_by):
    """{cell id: (r, g, b)} for a core.Mesh whose row c is cell id c + 1."""
    if color_by == "Cell type":
        return {c + 1: TYPE_COLORS.get(t, (0.6, 0.6, 0.6))
                for c, t in enumerate(mesh.types.tolist())}
    if color_by == "Scaled Jacobian":
        sj = core.cell_metrics(mesh)[0]
        return {c + 1: sj_color(v) for c, v in enumerate(sj.tolist())}
    return {}


def _second_order(fem):
    """Whether a FemMesh's volumes are quadratic (more nodes than corners)."""
    volumes = fem.Volumes
    return bool(volumes) and len(fem.getElementNodes(volumes[0])) > 8


class VPHexMesh(VPBaseHexDomObject):
    """View provider of HexDom Mesh objects."""

    def add_properties(self, vobj):
        if not hasattr(vobj, "ColorBy"):
            vobj.addProperty("App::PropertyEnumeration", "ColorBy", "HexDom",
                             "Colour cells by type (hex blue, prism orange, tet magenta) or by "
                             "scaled Jacobian (red 0, yellow 0.5, green 1, dark red inverted); a "
                             "second-order mesh is drawn plain (FreeCAD colours quadratic cells' "
                             "faces wrongly)")
            vobj.ColorBy = COLOR_BY
            vobj.ColorBy = "Cell type"

    def onChanged(self, vobj, prop):
        if prop == "ColorBy":
            self.recolor(vobj)

    def updateData(self, obj, prop):
        # FreeCAD calls this before ViewProviderFemMesh rebuilds its nodes from the new FemMesh,
        # and the rebuild drops ElementColor: recolour once control is back in the event loop.
        if prop == "FemMesh" and getattr(obj, "ViewObject", None) is not None:
            self.schedule_recolor(obj.ViewObject)

    def schedule_recolor(self, vobj):
        if getattr(self, "_recolor_pending", False):
            return
        self._recolor_pending = True
        from PySide import QtCore
        # Keep names, not vobj: if the object is deleted before the timer fires (an aborted
        # transaction, an undo), touching its dead view provider crashes FreeCAD.
        doc_name, obj_name = vobj.Object.Document.Name, vobj.Object.Name

        def run():
            self._recolor_pending = False
            if doc_name not in FreeCAD.listDocuments():
                return
            obj = FreeCAD.getDocument(doc_name).getObject(obj_name)
            view = getattr(obj, "ViewObject", None) if obj is not None else None
            if view is None or view.Proxy is not self:
                return
            try:
                self.recolor(view)
            except (ReferenceError, RuntimeError):
                pass  # the object was deleted (or its document closed) meanwhile

        QtCore.QTimer.singleShot(0, run)

    def claimChildren(self):
        """The inputs a generated mesh is made from sit under it in the tree."""
        obj = getattr(self, "Object", None)
        links = [getattr(obj, name, None) for name in ("Segmentation", "Polycube")]
        return [link for link in links if link is not None]

    def recolor(self, vobj):
        """Sets ElementColor from ColorBy; errors go to the report view, never up."""
        obj = vobj.Object
        color_by = getattr(vobj, "ColorBy", "Cell type")
        try:
            if color_by == "Plain" or obj.FemMesh.NodeCount == 0 or _second_order(obj.FemMesh):
                # FreeCAD 0.20 binds ElementColor one colour per drawn face, and draws each face of
                # a quadratic element as several: the colours would shift onto other cells and
                # leave the rest green. A second-order mesh is drawn in its plain colour.
                colors = {}
            else:
                mesh, _, cell_ids = femmesh.from_femmesh(obj.FemMesh, with_ids=True, corners_only=True)
                by_row = cell_colors(mesh, color_by)
                colors = {int(cell_ids[row - 1]): rgb for row, rgb in by_row.items()}
            vobj.ElementColor = colors
        except (core.Error, ValueError) as e:
            FreeCAD.Console.PrintError("HexDom: cannot colour {}: {}\n".format(obj.Label, e))
