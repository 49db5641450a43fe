"""App-side conversions without GUI: core arrays to and from FreeCAD objects (Fem.FemMesh), FEM
set-up helpers and readers core does not provide."""
