"""Creates HexDom document objects; attaches view providers only when the GUI is up, so that
scripts and tests run headless (the ObjectsFem role)."""

import FreeCAD


def make_hex_mesh(doc, mesh=None, name="HexDomMesh"):
    """Adds a HexDom Mesh object to ``doc``, holding the core.Mesh ``mesh`` if given."""
    obj = doc.addObject("Fem::FemMeshObjectPython", name)
    from .objects import hex_mesh
    hex_mesh.HexMesh(obj)
    if mesh is not None:
        hex_mesh.store_mesh(obj, mesh)
    if FreeCAD.GuiUp:
        from .viewproviders import view_hex_mesh
        view_hex_mesh.VPHexMesh(obj.ViewObject)
    return obj
