"""The automatic structure's patch surface should have a polycube boundary, so that the Build
Polycube panel can check (and a user edit) an automatic Polycube against its own patches, as it
does for hand-made ones (issue 9: "keeping every intermediate editable in the dialogs")."""

from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
BRACKET = REPO / "examples" / "data" / "bracket.step"


@pytest.mark.xfail(strict=True, reason=(
    "autopolycube's cut along the grid leaves sliver triangles (area 1.3e-9 against a mean of "
    "1.15 on bracket.step) that polycube_boundary refuses as degenerate"))
def test_automatic_patches_have_a_polycube_boundary(core):
    if not core.has_opencascade():
        pytest.skip("_hexdom built without OpenCASCADE")
    V, F, face = core.tessellate_file(str(BRACKET))
    labels = core.segment(core.Surface(V, F, face))
    result = core.autopolycube(labels, level=1)
    patches = result.patches
    n = np.cross(patches.V[patches.F[:, 1]] - patches.V[patches.F[:, 0]],
                 patches.V[patches.F[:, 2]] - patches.V[patches.F[:, 0]])
    area = 0.5 * np.linalg.norm(n, axis=1)
    boundary = core.polycube_boundary(patches)  # raises GeometryError on a degenerate triangle
    # One polycube face per patch, each over 4 corners (the patches are grid squares).
    assert len(boundary.faces) == len(np.unique(patches.patch))
    assert area.min() > 1e-6 * area.mean()
