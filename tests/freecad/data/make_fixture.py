"""Writes hexdom_mesh_<version>.FCStd, the reopen fixture of test_hex_mesh_object.py. Run once per
release inside FreeCAD with the workbench installed and commit the file:

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
    doc.saveAs(path)
    print("wrote", path)
    rc = 0
except Exception:  # report, then exit non-zero (freecadcmd would exit 0)
    import traceback
    traceback.print_exc()
sys.exit(rc)
