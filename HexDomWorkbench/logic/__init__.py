"""What the workbench computes without FreeCAD or Qt: numpy in, numpy out, the meshing itself
dispatched to ``core`` (the compiled ``_hexdom``). Importable in a plain Python; nothing here
imports FreeCAD, FreeCADGui, PySide or pivy (tests/python/test_workbench_imports.py checks it).

- triangles: normals, the one triangle adjacency, edges, connected regions, point merging;
- labels: polycube labels 1..6 (+X -X +Y -Y +Z -Z): names, the nearest axis, labels from
  normals, patches from labels, label edits, patch transfer between triangulations;
- cells: the faces of hex, prism and tet blocks (VTK order) and the boundary of a structure;
- stages: the core's stages as the workbench calls them (what the build offers, segment,
  check_patches, read_structure);
- undo_stack, patch_editing (PatchEditor, behind Edit Patches), polycube_building
  (PolycubeBuilder, behind Build Polycube).
"""
