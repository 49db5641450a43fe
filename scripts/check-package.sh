#!/usr/bin/env bash
# Installs the Debian package made by `make package` on this machine (as root), checks that what a
# user gets works without any build tree, then removes the package again (also on failure).
#   scripts/check-package.sh build/hexdom_0.1.0_amd64.deb
# Checks: dpkg -c lists the program, the module and the workbench; `hexdom --version`; `import
# _hexdom` from Debian's python3 finds the installed module; `hexdom mesh` meshes a box; FreeCAD
# (freecadcmd, a fresh HOME: no user Mod folder) imports the workbench from /usr/share/freecad/Mod
# and meshes a Part box through it; FreeCAD's GUI (xvfb) lists the workbench. Prints "PACKAGE OK".
set -euo pipefail
DEB=$(readlink -f "${1:?usage: $0 PACKAGE.deb}")
[ "$(id -u)" = 0 ] || { echo "check-package: run as root (it installs $DEB)" >&2; exit 2; }
if dpkg -s hexdom > /dev/null 2>&1; then
  echo "check-package: a hexdom package is installed already; remove it first" >&2
  exit 2
fi

echo "== dpkg -c"
dpkg -c "$DEB" | awk '{print $6}' | grep -E "usr/bin/hexdom$|_hexdom\.cpython|Mod/HexDom/(InitGui.py|HexDomWorkbench/core.py)$"
echo "== install"
apt-get install -y -q "$DEB" > /dev/null
trap 'echo "== remove"; apt-get remove -y -q hexdom > /dev/null; dpkg -s hexdom > /dev/null 2>&1 && exit 1; echo removed' EXIT

WORK=$(mktemp -d)
cd "$WORK"
export HOME=$WORK/home
mkdir -p "$HOME"
unset PYTHONPATH HEXDOM_BUILD_DIR

echo "== hexdom --version"
[ "$(command -v hexdom)" = /usr/bin/hexdom ]
hexdom --version

echo "== import _hexdom"
/usr/bin/python3 -c "import _hexdom; assert _hexdom.__file__.startswith('/usr/lib/python3/dist-packages/'), _hexdom.__file__; print(_hexdom.__file__, _hexdom.__version__, 'opencascade', _hexdom.has_opencascade())"

echo "== hexdom mesh"
cat > box.py <<'PY'
import sys
import FreeCAD, Part
Part.makeBox(40, 20, 10).exportStep(sys.argv[-1])
sys.exit(0)
PY
freecadcmd box.py "$WORK/box.step" > /dev/null 2>&1
[ -s box.step ]
hexdom mesh box.step -o box.vtu 2> mesh.log || { cat mesh.log; exit 1; }
[ -s box.vtu ]
grep "kept:" mesh.log

echo "== FreeCAD (App)"
cat > app.py <<'PY'
import os, sys
import FreeCAD
rc = 1
try:
    import HexDomWorkbench
    from HexDomWorkbench import core
    assert HexDomWorkbench.__file__.startswith("/usr/share/freecad/Mod/HexDom/"), HexDomWorkbench.__file__
    assert core._hexdom.__file__.startswith("/usr/lib/python3/dist-packages/"), core._hexdom.__file__
    doc = FreeCAD.newDocument("pkg")
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    objs = HexDomWorkbench.mesh_part(doc, box, size=4.0)
    mesh = objs["mesh"]
    print("FreeCAD meshed the box:", mesh.HexCount, "hex, worst SJ", round(mesh.MinHexSJ, 3))
    rc = 0 if mesh.HexCount > 0 and mesh.InvertedCount == 0 else 1
except Exception as e:
    import traceback
    traceback.print_exc()
sys.exit(rc)
PY
freecadcmd app.py 2>&1 | grep -E "FreeCAD meshed|Error|Traceback|assert" || true
freecadcmd app.py > app.log 2>&1 || { cat app.log; exit 1; }

echo "== FreeCAD (GUI)"
cat > gui.py <<'PY'
import os
import FreeCADGui
names = FreeCADGui.listWorkbenches()
with open(os.path.join(os.environ["HOME"], "workbenches.txt"), "w") as f:
    f.write("\n".join(sorted(names)))
os._exit(0)
PY
QTWEBENGINE_DISABLE_SANDBOX=1 LIBGL_ALWAYS_SOFTWARE=1 timeout 120 xvfb-run -a -s "-screen 0 1280x1024x24" \
  freecad gui.py > gui.log 2>&1 || true
grep -x HexDomWorkbench "$HOME/workbenches.txt" || { echo "the GUI does not list HexDomWorkbench"; cat gui.log; exit 1; }
echo "PACKAGE OK"
