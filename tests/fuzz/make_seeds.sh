#!/usr/bin/env bash
# Seed inputs of the fuzz targets (tests/fuzz/corpus/<reader>/), made with the program's own writers
# from a two-cell mesh and a tetrahedron's surface, plus the text formats (and the .msh files) written here.
#   tests/fuzz/make_seeds.sh build/bin/hexdom
set -e
HEXDOM=${1:-build/bin/hexdom}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
C=$HERE/corpus
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# The unit cube's corners in VTK's hexahedron order, for the legacy VTK files below.
CUBE='0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1'
# A hex and a wedge sharing a face, as legacy VTK (the reader's input and the others' source).
cat > "$T/two.vtk" <<VTK
# vtk DataFile Version 4.2
two cells
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 10 double
$CUBE
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
# LS-DYNA's second-order solids: the tet10 (ten-node format) and the unit cube as a 20-node hex
# (*ELEMENT_SOLID_H20).
"$HEXDOM" convert -i "$C/vtk/tet10.vtk" -o "$C/k/tet10.k" 2>/dev/null
python3 - "$T/hex20.vtk" <<'PY'
import sys
c = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
e = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
p = c + [tuple((c[a][k] + c[b][k]) / 2 for k in range(3)) for a, b in e]
with open(sys.argv[1], "w") as f:
    f.write("# vtk DataFile Version 4.2\nhex20\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 20 double\n")
    f.write("".join("%g %g %g\n" % q for q in p) + "CELLS 1 21\n20 " + " ".join(map(str, range(20))) + "\nCELL_TYPES 1\n25\n")
PY
"$HEXDOM" convert -i "$T/hex20.vtk" -o "$C/k/hex20.k" 2>/dev/null
# Gmsh .msh: the hex and the prism of two.vtk (the prism in Gmsh's order) in MSH 4.1 and 2.2,
# ASCII and binary, and a second-order tetrahedron (Gmsh type 11).
mkdir -p "$C/msh"
python3 - "$C/msh" <<'PY'
import struct, sys
out = sys.argv[1]
P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (2, 0, 0), (2, 0, 1)]
HEX, PRISM = [1, 2, 3, 4, 5, 6, 7, 8], [2, 9, 3, 6, 10, 7]
def ascii41():
    s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 5 \"solid\"\n$EndPhysicalNames\n"
    s += "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 1 5 0\n2 1 0 0 2 1 1 0 0\n$EndEntities\n"
    s += "$Nodes\n2 10 1 10\n3 1 0 8\n" + "".join(f"{i}\n" for i in range(1, 9))
    s += "".join(f"{x} {y} {z}\n" for x, y, z in P[:8]) + "3 2 1 2\n9\n10\n2 0 0 0.5 0.5 0.5\n2 0 1 0.5 0.5 0.5\n$EndNodes\n"
    s += "$Elements\n2 2 1 2\n3 1 5 1\n1 " + " ".join(map(str, HEX)) + "\n3 2 6 1\n2 " + " ".join(map(str, PRISM))
    return s + "\n$EndElements\n"
def ascii22():
    s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n" + "".join(f"{i + 1} {x} {y} {z}\n" for i, (x, y, z) in enumerate(P))
    s += "$EndNodes\n$Elements\n3\n1 5 2 5 1 " + " ".join(map(str, HEX)) + "\n2 6 2 0 2 " + " ".join(map(str, PRISM))
    return s + "\n3 2 2 0 3 1 2 3\n$EndElements\n$NodeData\n1\n\"x\"\n0\n3\n0\n1\n1\n1 0.5\n$EndNodeData\n"
def binary41():
    L = lambda f, *v: struct.pack("<" + f * len(v), *v)
    s = b"$MeshFormat\n4.1 1 8\n" + L("i", 1) + b"\n$EndMeshFormat\n$Entities\n" + L("Q", 0, 0, 0, 2)
    s += L("i", 1) + L("d", 0, 0, 0, 1, 1, 1) + L("Q", 1) + L("i", 5) + L("Q", 0)
    s += L("i", 2) + L("d", 1, 0, 0, 2, 1, 1) + L("Q", 0) + L("Q", 0) + b"\n$EndEntities\n$Nodes\n"
    s += L("Q", 1, 10, 1, 10) + L("i", 3, 1, 0) + L("Q", 10) + L("Q", *range(1, 11)) + L("d", *[c for p in P for c in p])
    s += b"\n$EndNodes\n$Elements\n" + L("Q", 2, 2, 1, 2) + L("i", 3, 1, 5) + L("Q", 1) + L("Q", 1, *HEX)
    s += L("i", 3, 2, 6) + L("Q", 1) + L("Q", 2, *PRISM) + b"\n$EndElements\n"
    return s
def binary22():
    B = lambda f, *v: struct.pack(">" + f * len(v), *v)  # big-endian, as the check int says
    s = b"$MeshFormat\n2.2 1 8\n" + B("i", 1) + b"\n$EndMeshFormat\n$Nodes\n10\n"
    s += b"".join(B("i", i + 1) + B("d", *p) for i, p in enumerate(P)) + b"\n$EndNodes\n$Elements\n2\n"
    s += B("i", 5, 1, 2, 1, 5, 1, *HEX) + B("i", 6, 1, 2, 2, 0, 2, *PRISM) + b"\n$EndElements\n"
    return s
def tet10():
    T = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    E = [(0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1)]
    Q = T + [tuple((T[a][k] + T[b][k]) / 2 for k in range(3)) for a, b in E]
    s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 10 1 10\n3 1 0 10\n" + "".join(f"{i}\n" for i in range(1, 11))
    s += "".join(f"{x} {y} {z}\n" for x, y, z in Q) + "$EndNodes\n$Elements\n1 1 1 1\n3 1 11 1\n1 "
    return s + " ".join(map(str, range(1, 11))) + "\n$EndElements\n"
for name, data in [("two_41_ascii.msh", ascii41()), ("two_22_ascii.msh", ascii22()), ("two_41_binary.msh", binary41()),
                   ("two_22_binary_be.msh", binary22()), ("tet10_41.msh", tet10())]:
    with open(f"{out}/{name}", "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)
PY
# The user-data checks: a unit cube's surface with one part id per face (surface_checks), and its
# polycube structure, one hex block, and two hex blocks splitting it (structure).
mkdir -p "$C/surface_checks" "$C/structure"
cat > "$T/cube_faces.vtk" <<VTK
# vtk DataFile Version 4.2
cube faces
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 8 double
$CUBE
CELLS 6 30
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 1 2 6 5
4 2 3 7 6
4 3 0 4 7
CELL_TYPES 6
9
9
9
9
9
9
CELL_DATA 6
SCALARS region int 1
LOOKUP_TABLE default
1
2
3
4
5
6
VTK
"$HEXDOM" convert -i "$T/cube_faces.vtk" -o "$C/surface_checks/cube_faces.k" 2>/dev/null
cp "$C/k/tet_shells.k" "$C/surface_checks/tet.k"
cat > "$T/one_block.vtk" <<VTK
# vtk DataFile Version 4.2
one block
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 8 double
$CUBE
CELLS 1 9
8 0 1 2 3 4 5 6 7
CELL_TYPES 1
12
VTK
"$HEXDOM" convert -i "$T/one_block.vtk" -o "$C/structure/one_block.k" 2>/dev/null
sed -e 's/^POINTS 8 double/POINTS 12 double/' -e 's/^CELLS 1 9/CELLS 2 18/' -e 's/^8 0 1 2 3 4 5 6 7$/8 0 8 9 3 4 10 11 7\n8 8 1 2 9 10 5 6 11/' \
  -e 's/^CELL_TYPES 1/CELL_TYPES 2\n12/' -e 's/^0 1 1$/0 1 1\n0.5 0 0\n0.5 1 0\n0.5 0 1\n0.5 1 1/' "$T/one_block.vtk" > "$T/two_blocks.vtk"
"$HEXDOM" convert -i "$T/two_blocks.vtk" -o "$C/structure/two_blocks.k" 2>/dev/null
printf '0 0.0 0.0 0.0\n3 1.0 1.0 1.0\n' > "$C/corner_points/corners.txt"
printf '# sharp nodes\n0\n1 7\n12\n' > "$C/sharp_nodes/sharp.txt"
printf '# triangle label\n0 0\n1 5\n\n2 3\n' > "$C/manual_labels/labels.txt"
ls -l "$C"/*
