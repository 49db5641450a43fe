"""View provider of HexDom Surface: the triangles coloured by CAD face (or file part) id, with the
face boundaries drawn as lines."""

import numpy as np

from ..logic.triangles import all_edges, boundary_edges
from . import coin_mesh
from .view_base import VPBaseHexDomObject

COLOR_BY = ["Face", "Plain"]


class VPSurface(coin_mesh.VPCoinBase, VPBaseHexDomObject):
    """View provider of HexDom Surface objects."""

    DATA_PROPERTIES = ("Points", "Triangles", "FaceId")
    VIEW_PROPERTIES = ("ColorBy",)

    def add_properties(self, vobj):
        if not hasattr(vobj, "ColorBy"):
            vobj.addProperty("App::PropertyEnumeration", "ColorBy", "HexDom",
                             "Colour triangles by CAD face id (one colour per face) or plain")
            vobj.ColorBy = COLOR_BY
            vobj.ColorBy = "Face"

    def build(self, obj, vobj, scene):
        arrays = coin_mesh.triangle_arrays(obj)
        ids = np.array(obj.FaceId, np.int64)
        if arrays is None or len(ids) != len(arrays[1]):
            return False
        V, F = arrays
        if getattr(vobj, "ColorBy", "Face") == "Plain":
            material, colors = np.zeros(len(F), np.int64), [(0.75, 0.75, 0.78)]
        else:
            material, colors = coin_mesh.palette_by_id(ids)
        scene.set(V, F, material, colors, boundary_edges(F, ids),
                  all_edges(F))
        return True

    def claimChildren(self):
        source = getattr(getattr(self, "Object", None), "Source", None)
        return [source] if source is not None else []
