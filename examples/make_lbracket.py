"""Makes the bundled example: an L-shaped bracket with a ramp, bent smoothly, as a segmented
surface (one patch per polycube face) and its polycube structure (3 hex blocks and 1 prism block).

Run:  /usr/bin/python3 examples/make_lbracket.py [outdir]   (needs the built _hexdom module)
Writes lbracket_patches.k and lbracket_structure.k.
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from HexDomWorkbench import core  # noqa: E402

# Structure in polycube coordinates: unit cubes C1 (0,0), C2 (1,0), C3 (0,1) in x-y, z in [0,1],
# and a ramp (prism) on top of C2.
HEXES = [(0, 0), (1, 0), (0, 1)]
CORNER = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEX_FACES = [(0, 4, 7, 3), (1, 2, 6, 5), (0, 1, 5, 4), (3, 7, 6, 2), (0, 3, 2, 1), (4, 5, 6, 7)]
WEDGE = [(1, 0, 1), (2, 0, 1), (1, 0, 2), (1, 1, 1), (2, 1, 1), (1, 1, 2)]
WEDGE_FACES = [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)]
RES = 8  # triangles per face edge


def bend(p):
    """A smooth, curving deformation so that the patch maps have real work to do."""
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    return np.stack([x + 0.08 * np.sin(2.0 * y), y + 0.06 * np.sin(1.5 * x + z),
                     z * (1.0 + 0.12 * x) + 0.05 * np.cos(1.7 * y)], axis=-1) * 10.0


def main(outdir):
    blocks = []  # (type, [points])
    for ox, oy in HEXES:
        blocks.append((12, [(ox + a, oy + b, c) for a, b, c in CORNER]))
    blocks.append((13, WEDGE))
    verts = {}

    def vid(p):
        key = tuple(round(float(c), 9) for c in p)
        return verts.setdefault(key, len(verts))

    cells = []
    for t, pts in blocks:
        cells.append((t, [vid(p) for p in pts]))
    # Boundary faces: faces used by one block.
    count = {}
    for t, ids in cells:
        for f in (HEX_FACES if t == 12 else WEDGE_FACES):
            key = tuple(sorted(ids[i] for i in f))
            count[key] = count.get(key, 0) + 1
    Vs = np.array(sorted(verts, key=verts.get), dtype=float)
    sverts, tris, patch = {}, [], []

    def sid(p):
        key = tuple(round(float(c), 9) for c in p)
        return sverts.setdefault(key, len(sverts))

    for t, ids in cells:
        for f in (HEX_FACES if t == 12 else WEDGE_FACES):
            fid = [ids[i] for i in f]
            if count[tuple(sorted(fid))] != 1:
                continue
            pid = len(set(patch)) + 1
            c = Vs[fid]
            if len(f) == 4:  # bilinear grid, two triangles per cell, outward as the face
                for j in range(RES):
                    for i in range(RES):
                        def q(a, b):
                            s, u = a / RES, b / RES
                            return sid((1 - s) * (1 - u) * c[0] + s * (1 - u) * c[1] + s * u * c[2] + (1 - s) * u * c[3])
                        a, b, cc, d = q(i, j), q(i + 1, j), q(i + 1, j + 1), q(i, j + 1)
                        tris += [(a, b, cc), (a, cc, d)]
                        patch += [pid, pid]
            else:  # triangle lattice
                def q(a, b):
                    return sid(c[0] + a / RES * (c[1] - c[0]) + b / RES * (c[2] - c[0]))
                for j in range(RES):
                    for i in range(RES - j):
                        tris.append((q(i, j), q(i + 1, j), q(i, j + 1)))
                        patch.append(pid)
                        if i + j + 2 <= RES:
                            tris.append((q(i + 1, j), q(i + 1, j + 1), q(i, j + 1)))
                            patch.append(pid)
    SV = bend(np.array(sorted(sverts, key=sverts.get), dtype=float))
    surface = core.Surface(SV, np.array(tris, dtype=np.int32), np.array(patch, dtype=np.int32))
    core.write_surface(os.path.join(outdir, "lbracket_patches.k"), surface)
    C = np.full((len(cells), 8), -1, dtype=np.int32)
    for r, (t, ids) in enumerate(cells):
        C[r, :len(ids)] = ids
    structure = core.Mesh(bend(Vs), C, np.array([t for t, _ in cells], dtype=np.int32),
                          np.arange(1, len(cells) + 1, dtype=np.int32))
    core.write_mesh(os.path.join(outdir, "lbracket_structure.k"), structure)
    print(f"wrote {len(tris)} triangles in {len(set(patch))} patches and {len(cells)} blocks to {outdir}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "data"))
