#!/usr/bin/env bash
# make demo: mesh the bundled L-bracket (made by examples/make_lbracket.py) and report its quality.
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
OUT=out/demo
mkdir -p "$OUT"
"$BUILD/bin/hexdom" generate -i examples/data/lbracket_patches.k -p examples/data/lbracket_structure.k \
  -s 3 -o "$OUT/lbracket.vtu" --report "$OUT/lbracket_quality.json"
"$BUILD/bin/hexdom" convert -i examples/data/lbracket_structure.k -o "$OUT/lbracket_structure.vtk"
echo "demo: mesh $OUT/lbracket.vtu (open it in ParaView or FreeCAD), quality report $OUT/lbracket_quality.json"
