"""Writes hexdom_mesh_<version>.FCStd (the reopen fixture of test_hex_mesh_object.py) unless it
exists, and hexdom_pipeline_<version>.FCStd (test_api_pipeline.py). Run once per release inside
FreeCAD with the workbench installed and commit the files:

    freecadcmd tests/freecad/data/make_fixture.py
"""

import os
import sys

rc = 1
try:
    import FreeCAD
    import HexDomWorkbench
    from HexDomWorkbench import core, make

    here = os.environ.get("HEXDOM_FC_FIXTURE_DIR") or os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.dirname(here))
    import fc_testdata

    doc = FreeCAD.newDocument("Fixture")
    make.make_hex_mesh(doc, core.Mesh(*fc_testdata.mixed_sample()), "HexDomMesh")
    doc.recompute()
    path = os.path.join(here, "hexdom_mesh_{}.FCStd".format(HexDomWorkbench.__version__))
    if not os.path.exists(path):  # one per release: an older layout must keep opening
        doc.saveAs(path)
        print("wrote", path)

    # Every pipeline object (Surface, Segmentation with an edit, Polycube, generated Mesh), at
    # level 1 to keep the file small. The example files are named by absolute path: recomputing
    # the Surface or Segmentation elsewhere needs them, the Mesh does not.
    doc = FreeCAD.newDocument("PipelineFixture")
    objs = HexDomWorkbench.make_document_objects(
        doc, patch_file=fc_testdata.example_path("lbracket_patches.k"),
        structure_file=fc_testdata.example_path("lbracket_structure.k"), level=1, improve=True)
    seg = objs["segmentation"]
    HexDomWorkbench.set_labels(seg, [0], seg.Labels[0])  # an edit that changes nothing
    HexDomWorkbench.recompute_document(doc)
    path = os.path.join(here, "hexdom_pipeline_{}.FCStd".format(HexDomWorkbench.__version__))
    doc.saveAs(path)
    print("wrote", path, sorted(o.Name for o in objs.values()))
    rc = 0
except Exception:  # report, then exit non-zero (freecadcmd would exit 0)
    import traceback
    traceback.print_exc()
sys.exit(rc)
