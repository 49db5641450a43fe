"""Polycube labels, numbered as in the core: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z; patch ids are
positive integers, one per connected region a polycube face maps to. Label algebra on numpy
arrays: the nearest axis, labels from normals, patches from labels, user edits of labels, and
patch ids carried over from another triangulation."""

import numpy as np

from .. import core
from ..core import LABEL_NAMES
from .triangles import connected_regions, nearest_rows, triangle_adjacency

# Direction of label l is AXES[l - 1].
AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
LABEL_NUMBERS = {name: number for number, name in LABEL_NAMES.items()}


def label_number(label):
    """1..6 from a label number or name ("+X" ... "-Z"); ValueError for anything else."""
    if isinstance(label, str):
        if label.strip().upper() not in LABEL_NUMBERS:
            raise ValueError("label '{}' is not one of +X -X +Y -Y +Z -Z".format(label))
        return LABEL_NUMBERS[label.strip().upper()]
    label = int(label)
    if not 1 <= label <= 6:
        raise ValueError("label {} is not one of 1..6 (+X -X +Y -Y +Z -Z)".format(label))
    return label


def nearest_label(normals):
    """Label (1..6) of the axis nearest each row of ``normals`` (#N x 3, or one vector: an
    array of one label): the core's segmentation::nearest_label."""
    return core.nearest_label(normals)


def labels_from_normals(V, F, patch=None, frame=None, stretch=None):
    """Polycube label per triangle: the axis nearest its normal, or with ``patch`` the axis
    nearest the area-weighted mean normal of the triangle's patch (one label per patch). frame:
    a 3 x 3 rotation whose axes the labels name (None: the model's); stretch: factors along its
    axes the surface is stretched by first (the Segmentation's Stretch; None: none). The core's
    segmentation::labels_from_normals."""
    return core.labels_from_normals(V, F, patch, frame, stretch)


def patches_from_labels(F, labels):
    """Patch id (1-based) per triangle: the connected regions of equal label."""
    return connected_regions(F, labels) + 1


def apply_label_edits(F, labels, patches, triangles, new_labels, keep_patches):
    """Applies user overrides (``triangles[i]`` gets ``new_labels[i]``; a later entry wins).

    Returns (labels, patches). With ``keep_patches`` (patches given by a file or the CAD faces)
    patch ids stay as they are, and each edited triangle joins the patch of a neighbour that has
    its new label (regions without such a neighbour get new ids); otherwise patches are the
    connected regions of equal label.
    """
    labels = np.array(labels, np.int32)
    patches = np.array(patches, np.int32)
    triangles = np.asarray(triangles, np.int64)
    new_labels = np.asarray(new_labels, np.int32)
    if len(triangles) == 0:
        return labels, patches
    labels[triangles] = new_labels
    if not keep_patches:
        return labels, patches_from_labels(F, labels)
    edited = np.zeros(len(labels), bool)
    edited[triangles] = True
    adjacency = triangle_adjacency(F)
    pairs = adjacency[labels[adjacency[:, 0]] == labels[adjacency[:, 1]]]
    neighbours = {}
    for a, b in pairs.tolist():
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    resolved = ~edited
    frontier = [t for t in np.flatnonzero(edited).tolist()
                if any(resolved[n] for n in neighbours.get(t, ()))]
    while frontier:  # grow unedited patches into edited triangles of the same label
        nxt = []
        for t in frontier:
            if resolved[t]:
                continue
            for n in neighbours.get(t, ()):
                if resolved[n]:
                    patches[t] = patches[n]
                    resolved[t] = True
                    break
            if resolved[t]:
                nxt += [n for n in neighbours.get(t, ()) if not resolved[n]]
        frontier = nxt
    left = np.flatnonzero(~resolved)
    if len(left):  # edited regions touching no patch of their label: new patches
        region = connected_regions(F, np.where(resolved, -1, labels), adjacency=adjacency)
        next_id = int(patches.max()) + 1
        for r in np.unique(region[left]).tolist():
            patches[(region == r) & ~resolved] = next_id
            next_id += 1
    return labels, patches


def transfer_patches(source, target):
    """Patch id of the nearest ``source`` triangle (by centroid) for each ``target`` triangle: the
    paper's patch files are segmentations of slightly different triangulations."""
    cs = np.asarray(source.V)[np.asarray(source.F)].mean(axis=1)
    ct = np.asarray(target.V)[np.asarray(target.F)].mean(axis=1)
    return np.asarray(source.patch)[nearest_rows(cs, ct)].astype(np.int32)
