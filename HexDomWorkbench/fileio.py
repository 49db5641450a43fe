"""File > Open / Import / Export of HexDom meshes (.k, .vtk, .vtu, .inp, Gmsh .msh),
registered in Init.py. FreeCAD calls open(filename), insert(filename, docname) and
export(objects, filename); the same functions serve macros and the HexDom_ImportMesh /
HexDom_ExportMesh commands.

Reading and writing go through core (read_mesh / write_mesh). core.Error propagates to the caller.
"""

import os

import FreeCAD

from . import core

READ_EXTENSIONS = (".k", ".vtk", ".vtu", ".inp", ".msh")
WRITE_EXTENSIONS = (".vtk", ".vtu", ".k", ".inp", ".msh")


def read_mesh(path):
    """core.Mesh from a .k, .vtk, .vtu, .inp or .msh file (raises core.Error)."""
    return core.read_mesh(path)


def import_mesh(path, doc=None, name=None):
    """Reads ``path`` into a new HexDom Mesh object of ``doc`` (the active or a new document);
    recomputes and returns the object."""
    from . import make

    mesh = read_mesh(path)
    if doc is None:
        doc = FreeCAD.ActiveDocument or FreeCAD.newDocument()
    base = os.path.splitext(os.path.basename(path))[0]
    obj = make.make_hex_mesh(doc, mesh, name or "HexDomMesh")
    obj.Label = base
    obj.SourceFile = os.path.abspath(path)
    doc.recompute()
    counts = mesh.counts
    FreeCAD.Console.PrintMessage(
        "HexDom: imported {}: {} nodes, {} hex, {} prism, {} tet\n".format(
            path, len(mesh.V), counts["hex"], counts["prism"], counts["tet"]))
    return obj


def export_mesh(obj, path, binary=False):
    """Writes the mesh of a HexDom Mesh (or any FEM mesh object) with core.write_mesh."""
    from .objects import hex_mesh

    if not hasattr(obj, "FemMesh"):
        raise ValueError("{} is not a FEM mesh object".format(obj.Label))
    mesh = hex_mesh.get_mesh(obj)
    core.write_mesh(path, mesh, binary=binary)
    FreeCAD.Console.PrintMessage("HexDom: wrote {} cells to {}\n".format(len(mesh.types), path))


# FreeCAD's import / export entry points.
def open(filename):  # noqa: A001 (the name FreeCAD calls)
    name = os.path.splitext(os.path.basename(filename))[0]
    doc = FreeCAD.newDocument(_doc_name(name))
    doc.Label = name
    import_mesh(filename, doc)
    return doc


def insert(filename, docname):
    try:
        doc = FreeCAD.getDocument(docname)
    except NameError:
        doc = FreeCAD.newDocument(docname)
    FreeCAD.setActiveDocument(doc.Name)
    import_mesh(filename, doc)


def export(objects, filename):
    meshes = [o for o in objects if hasattr(o, "FemMesh")]
    if len(meshes) != 1:
        raise ValueError("select exactly one mesh object to export ({} selected)".format(
            len(meshes)))
    export_mesh(meshes[0], filename)


def _doc_name(name):
    cleaned = "".join(c if c.isalnum() else "_" for c in name)
    if not cleaned or cleaned[0].isdigit():
        cleaned = "Mesh_" + cleaned
    return cleaned
