"""Creates HexDom document objects; attaches view providers only when the GUI is up, so that
scripts and tests run headless (the ObjectsFem role). Nothing here recomputes. FreeCAD is
imported on the first call, so that importing this module (through api) stays FreeCAD-free."""

import os

from .objects import hex_mesh, polycube, segmentation, tessellation


def _gui_up():
    import FreeCAD
    return bool(FreeCAD.GuiUp)


def _hide(obj):
    if obj is not None and getattr(obj, "ViewObject", None) is not None and _gui_up():
        obj.ViewObject.Visibility = False


def make_hex_mesh(doc, mesh=None, name="HexDomMesh", segmentation=None, polycube=None,
                  level=None, improve=None, base_mesh=None):
    """Adds a HexDom Mesh object to ``doc``, holding the core.Mesh ``mesh`` if given.

    With ``segmentation`` and ``polycube`` (HexDom objects) the mesh is generated from them on
    recompute, at ``level`` (default 2) and improved if ``improve`` (default True); with
    ``base_mesh`` (a FEM mesh object) it is an (improved) copy of that mesh.
    """
    obj = doc.addObject("Fem::FemMeshObjectPython", name)
    hex_mesh.HexMesh(obj)
    if mesh is not None:
        hex_mesh.store_mesh(obj, mesh)
    if segmentation is not None:
        obj.Segmentation = segmentation
    if polycube is not None:
        obj.Polycube = polycube
    if base_mesh is not None:
        obj.BaseMesh = base_mesh
    if level is not None:
        obj.Level = int(level)
    if improve is not None:
        obj.Improve = bool(improve)
    if _gui_up():
        from .viewproviders import view_hex_mesh
        view_hex_mesh.VPHexMesh(obj.ViewObject)
        for link in (segmentation, polycube, base_mesh):
            _hide(link)
    return obj


def make_surface(doc, source=None, surface=None, path=None, size=0.0, deflection=0.0, angle=None,
                 name="HexDomSurface"):
    """Adds a HexDom Surface to ``doc``: the tessellation of the Part object ``source`` (Size,
    Deflection, Angle as given), the triangles of the file ``path``, or the core.Surface
    ``surface`` (kept as is)."""
    obj = doc.addObject("App::FeaturePython", name)
    tessellation.Surface(obj)
    if source is not None:
        obj.Source = source
    if path:
        obj.SourceFile = path
    obj.Size = float(size or 0.0)
    obj.Deflection = float(deflection or 0.0)
    if angle is not None:
        obj.Angle = float(angle)
    if surface is not None:
        tessellation.store_surface(obj, surface)
    if _gui_up():
        from .viewproviders import view_tessellation
        view_tessellation.VPSurface(obj.ViewObject)
        _hide(source)
    return obj


def make_segmentation(doc, surface, method=None, patch_file=None, name="HexDomSegmentation"):
    """Adds a HexDom Segmentation of the HexDom Surface ``surface``. ``method`` is "Automatic",
    "Surface patches" or "Patch file" (default: "Patch file" when ``patch_file`` is given, else
    "Automatic")."""
    obj = doc.addObject("App::FeaturePython", name)
    segmentation.Segmentation(obj)
    obj.Surface = surface
    if patch_file:
        obj.PatchFile = patch_file
    obj.Method = method or ("Patch file" if patch_file else "Automatic")
    if _gui_up():
        from .viewproviders import view_segmentation
        view_segmentation.VPSegmentation(obj.ViewObject)
        _hide(surface)
    return obj


def make_polycube(doc, structure=None, path=None, name="HexDomPolycube", segmentation=None,
                  size=0.0, level=None):
    """Adds a HexDom Polycube holding the structure core.Mesh ``structure`` (read from ``path``
    on recompute when no structure is given). With ``segmentation`` (a HexDom Segmentation) and
    no structure it is automatic: Mode "Automatic", blocks of ``size`` * 2^``level`` built on
    recompute by core.autopolycube (size 0: bounding-box diagonal / 30; level default 1)."""
    obj = doc.addObject("App::FeaturePython", name)
    polycube.Polycube(obj)
    if segmentation is not None:
        obj.Segmentation = segmentation
        obj.Size = float(size or 0.0)
        if level is not None:
            obj.Level = int(level)
        if structure is None and not path:
            obj.Mode = "Automatic"
    if structure is not None:
        polycube.store_structure(obj, structure)
        if path:
            obj.LoadedFile = os.path.abspath(path)
    if path:
        obj.SourceFile = path
    if _gui_up():
        from .viewproviders import view_polycube
        view_polycube.VPPolycube(obj.ViewObject)
    return obj
