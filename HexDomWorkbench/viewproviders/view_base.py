"""Boilerplate shared by HexDom view providers."""

import FreeCAD

from .. import paths


class VPBaseHexDomObject:
    """Base view provider: icon named after the object's Type ("HexDom::Mesh" ->
    Resources/icons/HexDom_Mesh.svg), view properties added idempotently."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self.add_properties(vobj)

    def add_properties(self, vobj):
        """Adds missing view properties; also called from attach, so restored documents get
        properties added after they were saved."""

    def attach(self, vobj):
        self.Object = vobj.Object
        self.ViewObject = vobj
        self.add_properties(vobj)

    def getIcon(self):
        obj = getattr(self, "Object", None)
        type_name = getattr(getattr(obj, "Proxy", None), "Type", "")
        if not type_name.startswith("HexDom::"):
            FreeCAD.Console.PrintLog("HexDom: no icon for {}\n".format(type_name))
            return ""
        return paths.icon(type_name.replace("::", "_"))

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None
