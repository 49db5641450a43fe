#!/usr/bin/env bash
# Seed inputs of the fuzz targets (tests/fuzz/corpus/<reader>/), made with the program's own writers
# from a two-cell mesh and a tetrahedron's surface, plus the text formats written here.
#   tests/fuzz/make_seeds.sh build/bin/hexdom
set -e
HEXDOM=${1:-build/bin/hexdom}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
C=$HERE/corpus
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# A hex and a wedge sharing a face, as legacy VTK (the reader's input and the others' source).
cat > "$T/two.vtk" <<'VTK'
# vtk DataFile Version 4.2
two cells
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 10 double
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
2 0 0
2 0 1
CELLS 2 16
8 0 1 2 3 4 5 6 7
6 1 8 2 5 9 6
CELL_TYPES 2
12
13
CELL_DATA 2
SCALARS region int 1
LOOKUP_TABLE default
1
2
VTK
cp "$T/two.vtk" "$C/vtk/two_ascii.vtk"
"$HEXDOM" convert -i "$T/two.vtk" -o "$C/vtk/two_binary.vtk" --binary 2>/dev/null
"$HEXDOM" convert -i "$T/two.vtk" -o "$C/k/two.k" 2>/dev/null
mkdir -p "$C/vtu" "$C/inp"
"$HEXDOM" convert -i "$T/two.vtk" -o "$C/vtu/two_base64.vtu" 2>/dev/null
"$HEXDOM" convert -i "$T/two.vtk" -o "$C/inp/two.inp" 2>/dev/null
# VTK's own layouts: ascii, and appended raw data compressed with zlib.
python3 - "$T/two.vtk" "$C/vtu" <<'PY'
import sys, vtk
r = vtk.vtkUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update()
for name, mode in (("two_ascii.vtu", "ascii"), ("two_appended_zlib.vtu", "appended")):
    w = vtk.vtkXMLUnstructuredGridWriter(); w.SetInputData(r.GetOutput()); w.SetFileName(sys.argv[2] + "/" + name)
    if mode == "ascii":
        w.SetDataModeToAscii()
    else:
        w.SetDataModeToAppended(); w.EncodeAppendedDataOff(); w.SetCompressorTypeToZLib()
    w.Write()
PY
# A tetrahedron's surface.
cat > "$C/obj/tet.obj" <<'OBJ'
# tetrahedron
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 2 3 4
f 1 4 3
OBJ
"$HEXDOM" convert -i "$C/obj/tet.obj" -o "$C/stl/tet_ascii.stl" 2>/dev/null
"$HEXDOM" convert -i "$C/obj/tet.obj" -o "$C/k/tet_shells.k" 2>/dev/null
"$HEXDOM" convert -i "$C/obj/tet.obj" -o "$C/vtk/tet_surface.vtk" 2>/dev/null
# The same surface as binary STL, and a second-order tetrahedron (VTK type 24).
python3 - "$C/stl/tet_binary.stl" <<'PY'
import struct, sys
P = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
T = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
with open(sys.argv[1], "wb") as f:
    f.write(b"binary tet".ljust(80, b" ") + struct.pack("<I", len(T)))
    for t in T:
        f.write(struct.pack("<12fH", 0, 0, 0, *[c for k in t for c in P[k]], 0))
PY
cat > "$C/vtk/tet10.vtk" <<'VTK'
# vtk DataFile Version 4.2
tet10
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 10 double
0 0 0
1 0 0
0 1 0
0 0 1
0.5 0 0
0.5 0.5 0
0 0.5 0
0 0 0.5
0.5 0 0.5
0 0.5 0.5
CELLS 1 11
10 0 1 2 3 4 5 6 7 8 9
CELL_TYPES 1
24
VTK
"$HEXDOM" convert -i "$C/vtk/tet10.vtk" -o "$C/inp/tet10.inp" 2>/dev/null
printf '0 0.0 0.0 0.0\n3 1.0 1.0 1.0\n' > "$C/corner_points/corners.txt"
printf '# sharp nodes\n0\n1 7\n12\n' > "$C/sharp_nodes/sharp.txt"
printf '# triangle label\n0 0\n1 5\n\n2 3\n' > "$C/manual_labels/labels.txt"
ls -l "$C"/*
