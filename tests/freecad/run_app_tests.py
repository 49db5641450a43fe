"""Runs the App tests with pytest inside FreeCAD's interpreter:

    freecadcmd tests/freecad/run_app_tests.py

(run.sh sets HEXDOM_FC_TEST_DIR and HEXDOM_FC_PYTEST_ARGS). freecadcmd exits 0 after an uncaught
exception, so every path ends in sys.exit with pytest's code.
"""

import os
import shlex
import sys

rc = 3
try:
    # Init.py must register file types without loading the compiled core.
    os.environ["HEXDOM_FC_CORE_AT_STARTUP"] = "1" if "HexDomWorkbench.core" in sys.modules else "0"
    import pytest

    test_dir = os.environ.get("HEXDOM_FC_TEST_DIR")
    if not test_dir:
        test_dir = os.path.dirname(os.path.abspath(__file__))
    args = [os.path.join(test_dir, "app"), "-p", "no:cacheprovider", "-rs"]
    args += shlex.split(os.environ.get("HEXDOM_FC_PYTEST_ARGS", ""))
    rc = int(pytest.main(args))
except Exception as e:  # report anything, then exit non-zero
    import traceback
    traceback.print_exc()
    print("run_app_tests: {}".format(e))
    rc = 3
sys.stdout.flush()
sys.exit(rc)
