"""Python API for macros and scripts: the whole pipeline, from a CAD part to a FEM mesh.

    import HexDomWorkbench as hexdom
    surface = hexdom.tessellate(shape, size=2.0)          # core.Surface, patch = CAD face number
    segmented = hexdom.segment(surface)                    # SegmentedSurface (labels, patches)
    mesh = hexdom.generate(segmented, structure, level=2)  # core.Mesh
    mesh = hexdom.improve(mesh, segmented)
    fem = hexdom.to_fem_mesh(mesh)                         # Fem.FemMesh
    objs = hexdom.make_document_objects(doc, patch_file=..., structure_file=...)

A facade: the names live in modules by concern, and this module only gathers them.

- logic.labels, logic.triangles: label algebra and triangle helpers (numpy);
- logic.stages: what the build offers, segment, check_patches, read_structure (the core's calls);
- shape_tessellation: a Part shape to a core.Surface (the core's OCCT, or FreeCAD's MeshPart);
- document: document objects from scripts, structure and patch files, label edits, recompute;
- part_meshing: Mesh Part (mesh_part and its stages);
- progress: Progress and Cancelled (progress bar, Cancel, worker thread for core calls);
- convert.femmesh: core.Mesh to and from Fem.FemMesh.

The package re-exports these names lazily, so ``import HexDomWorkbench`` never loads FreeCAD,
and importing this module does not either: FreeCAD is imported only inside the functions that
need it; ``segment``, ``generate``, ``improve`` and the patch helpers work in a plain Python with
numpy. The meshing itself is the compiled core's (``core``); nothing here meshes.

Optional stages of the core are used when the compiled module provides them (``core.segment``,
``core.check_patches``, ``core.tessellate_brep``); without them ``segment`` raises core.Error
("segmentation not available in this build") and ``tessellate`` uses FreeCAD's MeshPart.

Labels (polycube directions) are numbered as in the core: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z;
patch ids are positive integers, one per connected region a polycube face maps to.
"""

from . import core  # noqa: F401
from .convert.femmesh import from_femmesh as from_fem_mesh  # noqa: F401
from .convert.femmesh import to_femmesh as to_fem_mesh  # noqa: F401
from .core import generate, improve  # noqa: F401  (the same functions, FreeCAD-free)
from .document import (  # noqa: F401
    RecomputeError,
    clear_edits,
    export_structure,
    import_patches,
    import_structure,
    improve_object,
    make_document_objects,
    recompute_document,
    set_labels,
)
from .logic.labels import (  # noqa: F401
    AXES,
    LABEL_NAMES,
    apply_label_edits,
    label_number,
    labels_from_normals,
    nearest_label,
    patches_from_labels,
    transfer_patches,
)
from .logic.stages import (  # noqa: F401
    SegmentedSurface,
    check_patches,
    core_has,
    has_cad,
    has_segmentation,
    read_structure,
    segment,
)
from .logic.triangles import (  # noqa: F401
    connected_regions,
    triangle_adjacency,
    triangle_normals,
)
from .part_meshing import (  # noqa: F401
    MESH_PART_STAGES,
    MeshPartError,
    check_mesh_part,
    fill_mesh_part,
    make_mesh_part,
    mesh_part,
    part_size,
    run_pipeline,
)
from .progress import Cancelled, Progress  # noqa: F401
from .shape_tessellation import (  # noqa: F401
    MAX_TRIANGLES,
    curvature_length,
    default_size,
    remesh_to_size,
    tessellate,
)
