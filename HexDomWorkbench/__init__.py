"""HexDom for FreeCAD: hex-dominant volume meshes by polycubes.

Macro API (no GUI needed)::

    import HexDomWorkbench as hexdom
    mesh = hexdom.read_mesh("part.vtk")
    print(hexdom.quality_report(mesh)["hex"]["sj_min"])

    surface = hexdom.tessellate(part.Shape, size=2.0)    # FreeCAD needed from here on
    mesh = hexdom.generate(hexdom.segment(surface), hexdom.read_structure("s.k"), level=2)
    fem = hexdom.to_fem_mesh(hexdom.improve(mesh))
    objs = hexdom.make_document_objects(doc, patch_file="p.k", structure_file="s.k")
    objs = hexdom.mesh_part(doc, part_obj, size=2.0, level=1)   # no manual step: all four objects

The meshing itself lives in the compiled module ``_hexdom``; this package converts, displays and
dispatches. Importing it does not import FreeCAD: the names of ``api`` (which import FreeCAD only
when they need it) load on first use.
"""

from .core import (  # noqa: F401
    Error,
    GeometryError,
    InputError,
    Interrupt,
    Interrupted,
    Mesh,
    MeshingError,
    Surface,
    cell_metrics,
    generate,
    improve,
    quality_report,
    read_mesh,
    read_surface,
    write_mesh,
    write_surface,
)

from .version import __version__  # noqa: F401

# Names served lazily from .api (PEP 562), so that importing the package stays FreeCAD-free.
_API_NAMES = (
    "Cancelled", "LABEL_NAMES", "MeshPartError", "Progress", "RecomputeError",
    "SegmentedSurface", "apply_label_edits", "check_patches", "clear_edits", "export_structure",
    "from_fem_mesh", "has_cad", "has_segmentation", "import_patches", "import_structure",
    "improve_object", "labels_from_normals", "make_document_objects", "mesh_part",
    "patches_from_labels", "read_structure", "recompute_document", "segment", "set_labels",
    "tessellate", "to_fem_mesh", "transfer_patches",
)


def __getattr__(name):
    if name in _API_NAMES or name == "api":
        # An import statement (not importlib), so that the import graph test sees this edge;
        # "from . import api" would ask this very function for "api" first.
        import HexDomWorkbench.api as api
        return api if name == "api" else getattr(api, name)
    raise AttributeError("module {!r} has no attribute {!r}".format(__name__, name))


def __dir__():
    return sorted(set(globals()) | set(_API_NAMES))
