"""HexDom for FreeCAD: hex-dominant volume meshes by polycubes.

Macro API (no GUI needed)::

    import HexDomWorkbench as hexdom
    mesh = hexdom.read_mesh("part.vtk")
    print(hexdom.quality_report(mesh)["hex"]["sj_min"])

The meshing itself lives in the compiled module ``_hexdom``; this package converts, displays and
dispatches. Importing it does not import FreeCAD.
"""

from .core import (  # noqa: F401
    Error,
    GeometryError,
    InputError,
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

__version__ = "0.1.0"
