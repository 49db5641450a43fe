#!/usr/bin/env bash
# make demo: a CAD part meshed end to end with no manual step, then the hand-made example.
#   1. examples/data/bracket.step (an angle bracket with a hole and a fillet, made by
#      examples/make_bracket_step.py): hexdom mesh = tessellate -> segment -> automatic polycube
#      -> generate -> improve; writes the mesh, its quality report and the intermediate files.
#   2. the L-bracket from its hand-made patches and structure (examples/make_lbracket.py).
# Usage: examples/run_demo.sh [BUILD_DIR]; output in $HEXDOM_DEMO_OUT (default out/demo).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd)  # a relative BUILD_DIR is taken from the caller's directory
cd "$ROOT"
OUT=${HEXDOM_DEMO_OUT:-out/demo}
mkdir -p "$OUT"
HEXDOM="$BUILD/bin/hexdom"

start=$(date +%s%N)
"$HEXDOM" mesh examples/data/bracket.step -o "$OUT/bracket.vtu" --report "$OUT/bracket_quality.json" \
  --keep | tee "$OUT/bracket_quality.txt"
ms=$(( ($(date +%s%N) - start) / 1000000 ))
printf 'demo: bracket.step meshed end to end in %d.%03d s\n' $((ms / 1000)) $((ms % 1000))

"$HEXDOM" generate -i examples/data/lbracket_patches.k -p examples/data/lbracket_structure.k \
  -s 3 -o "$OUT/lbracket.vtu" --report "$OUT/lbracket_quality.json"
"$HEXDOM" convert -i examples/data/lbracket_structure.k -o "$OUT/lbracket_structure.vtk"

echo "demo: $OUT/bracket.vtu (quality: $OUT/bracket_quality.txt, .json; intermediate files:"
echo "      bracket_labels.k, bracket_structure.k, bracket_patches.k, bracket_polycube.vtk),"
echo "      $OUT/lbracket.vtu from the hand-made structure; open them in ParaView or FreeCAD"
