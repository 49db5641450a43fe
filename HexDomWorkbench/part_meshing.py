"""Mesh Part: a Part solid meshed with no manual step, as `hexdom mesh` does, every stage kept as
an editable document object (Surface -> Segmentation -> automatic Polycube -> Mesh). Creates
them (make_mesh_part), makes `hexdom mesh`'s choice on the Surface's triangles and sets it on the
objects (choose_mesh_part: one core call, in a worker thread under the GUI), recomputes and names
the stage at fault (check_mesh_part). The meshing is the core's; FreeCAD is imported only inside
the functions that need it.

The Mesh's Method chooses the path: "polycube" (the stages above), "overlay" (a grid laid over the
Surface: no Polycube object is made) or "auto" (the default: the core's choice, `hexdom mesh
--method auto`; when it keeps the overlay mesh, the Segmentation and the Polycube stay in the
document, editable, but the Mesh no longer uses the Polycube; its MeshingPath says "overlay" and its
PolycubeNote why the polycube lost)."""

from . import core, make
from .document import RecomputeError
from .logic.stages import core_has, has_cad
from .objects import hex_mesh, segmentation, tessellation
from .progress import Cancelled, Progress


MESH_PART_STAGES = (("surface", "tessellate"), ("segmentation", "segment"),
                    ("polycube", "automatic polycube"), ("mesh", "generate and improve"))


class MeshPartError(RecomputeError):
    """A stage of mesh_part failed: ``stage`` names it, ``objects`` holds the objects created
    (all kept in the document, the finished ones valid), the message is the core's."""

    def __init__(self, message, stage=None, objects=None):
        super().__init__(message)
        self.stage = stage
        self.objects = objects or {}


def part_size(shape):
    """Target element size mesh_part uses when given 0, as `hexdom mesh`: the bounding-box
    diagonal / 30; for a part lying at an angle (its faces fit axes turned from the model's,
    core.cube_frame on a first tessellation), the diagonal of the box square to those axes / 30."""
    size = shape.BoundBox.DiagonalLength / 30.0
    if has_cad() and core_has("cube_frame"):
        try:
            V, F, face = core.tessellate_brep(shape.exportBrepToString(), size=size)
        except core.Error:
            return size
        frame = core.cube_frame(core.Surface(V, F, face))
        if frame["turned"]:
            size = core.frame_diagonal(core.Surface(V, F, face), frame["rotation"]) / 30.0
    return size


def make_mesh_part(doc, part, size=0.0, level=1, improve=True, method="auto"):
    """Adds the four objects of mesh_part to ``doc`` without recomputing; returns them as a dict
    (surface, segmentation, polycube, mesh). ``method`` goes on the Mesh's Method; with "overlay"
    no Polycube is made (the dict has no polycube) and the Mesh meshes the Segmentation's Surface."""
    if method not in hex_mesh.METHODS:
        raise ValueError("method must be one of {}".format(", ".join(hex_mesh.METHODS)))
    shape = getattr(part, "Shape", None)
    if shape is None or shape.isNull() or not shape.Solids:
        raise ValueError("{}: select a Part solid to mesh".format(getattr(part, "Label", part)))
    size = float(size) if size and size > 0 else part_size(shape)
    if int(level) < 0:
        raise ValueError("level must be 0 or more")
    label = part.Label
    objs = {}
    # The tessellation of `hexdom mesh`: triangles of the element size, chords within size / 50.
    objs["surface"] = make.make_surface(doc, source=part, size=size, deflection=size / 50.0,
                                        angle=30.0)
    objs["segmentation"] = make.make_segmentation(doc, objs["surface"], method="Automatic")
    if method != "overlay":
        objs["polycube"] = make.make_polycube(doc, segmentation=objs["segmentation"], size=size,
                                              level=level)
    objs["mesh"] = make.make_hex_mesh(doc, segmentation=objs["segmentation"],
                                      polycube=objs.get("polycube"), level=level, improve=improve)
    if hasattr(objs["mesh"], "Method"):
        objs["mesh"].Method = method
    if "polycube" in objs:
        try:  # one Level for both: the blocks are made for the mesh's subdivision
            objs["mesh"].setExpression("Level", objs["polycube"].Name + ".Level")
        except (AttributeError, RuntimeError, ValueError):
            pass
    for key, suffix in (("surface", "_surface"), ("segmentation", "_segmentation"),
                        ("polycube", "_polycube"), ("mesh", "_mesh")):
        if key in objs:
            objs[key].Label = label + suffix
    return objs


def element_size(objs):
    """The element size of mesh_part's objects: the Polycube's Size, else (Method overlay: no
    Polycube) the Surface's."""
    poly = objs.get("polycube")
    return float((poly if poly is not None else objs["surface"]).Size.Value)


def use_overlay(objs):
    """The Mesh of mesh_part's objects keeps the overlay grid's mesh: it no longer uses the
    Polycube (link and Level expression removed, so that a Polycube the automatic polycube fails
    on does not hold the Mesh's recompute back), which stays in the document, editable (set the
    Mesh's Method to polycube and link it again to go back). MeshingPath says "overlay", which is
    what the Mesh rebuilds in Method auto without a Polycube."""
    mesh = objs["mesh"]
    try:
        mesh.setExpression("Level", None)
    except (AttributeError, RuntimeError, ValueError):
        pass
    if getattr(mesh, "Polycube", None) is not None:
        mesh.Polycube = None
    if hasattr(mesh, "MeshingPath") and mesh.MeshingPath != "overlay":
        mesh.MeshingPath = "overlay"


def choose_mesh_part(objs, run=None):
    """The candidate choice of `hexdom mesh` for mesh_part's objects: recomputes the Surface, runs
    core.mesh_surface on its triangles (the Polycube's Size and Level, the Mesh's Improve;
    segmentation edge weight, widths of holes, tet or hex blocks at apexes and the level drop
    chosen by measuring the meshes) and sets what it kept on the objects:
    Segmentation.EdgeWeight, Polycube.KeepWidths, .TetApexes and .Level (the Mesh's Level follows
    it), after putting the frame the faces fit (core.cube_frame) on Segmentation.Frame; when the
    mesh came from another tessellation (core.mesh_part tessellates again when the first one's
    labelling defeats the polycube or cells stay inverted after the snap), the Surface's Size and
    Deflection become that tessellation's. The rest is left to recompute, which rebuilds the kept
    candidate with ordinary, editable objects. The Mesh's Method goes to the core (method=); when
    the core keeps the overlay grid's mesh, the Mesh stops using the Polycube (use_overlay) and
    nothing is set on the Segmentation and the Polycube; the Mesh's PolycubeNote gets the core's
    polycube_note either way. The core call runs in a Progress (a worker thread
    under the GUI), or in ``run`` when given. Returns the core.MeshRun of the choice (core.mesh_part's,
    snapped; with a build without it, core.mesh_surface's on the Surface's triangles, not snapped),
    or None when the Surface or the choice failed or was cancelled: the objects keep their
    settings, and recomputing them reports the stage at fault (or cancelled)."""
    surface_obj, seg, poly = objs["surface"], objs["segmentation"], objs.get("polycube")
    surface_obj.Document.recompute([surface_obj])  # (obj.recompute() would leave it touched)
    state = surface_obj.State
    if "Invalid" in state or "Error" in state or not len(surface_obj.Triangles):
        return None
    surface = tessellation.get_surface(surface_obj)
    mesh = objs.get("mesh")
    # The frame the faces fit goes on the Segmentation first, and the choice is made in the frame
    # the objects will read back from it (a Rotation property: the same matrix to the last bit).
    if hasattr(seg, "Frame"):
        fit = core.cube_frame(surface)
        segmentation.set_frame(seg, fit["rotation"] if fit["turned"] else None)
    frame = segmentation.frame_matrix(seg)
    # `hexdom mesh`'s own path on the Surface's shape when the build has it (the snap, and another
    # tessellation when this one's labelling defeats the polycube or cells stay inverted after the
    # snap); else the choice among the candidates on the Surface's triangles.
    source = getattr(surface_obj, "Source", None)
    shape = getattr(source, "Shape", None)
    size = element_size(objs)
    whole = (hasattr(getattr(core, "_hexdom", None), "mesh_cad") and has_cad()
             and shape is not None and not shape.isNull()
             and abs(float(surface_obj.Size.Value) - size) <= 1e-12 * size)
    method = getattr(mesh, "Method", "auto")
    # align: the overlay grid is laid in the frame the faces fit when the Segmentation has one, as
    # the Mesh lays it (the polycube takes `frame`, which then overrides align).
    options = dict(size=size, level=int(poly.Level if poly is not None else getattr(mesh, "Level", 1)),
                   improve=bool(getattr(mesh, "Improve", True)), allow_inverted=True,
                   align=frame is not None, frame=frame, method=method)
    try:
        label = (poly if poly is not None else mesh if mesh is not None else surface_obj).Label
        with Progress("Choosing the mesh of " + surface_obj.Label, 1) as bar:
            if whole:
                chosen = (run or bar.run)("choose the mesh", core.mesh_part,
                                          shape.exportBrepToString(), **options)
            else:
                chosen = (run or bar.run)("choose the mesh", core.mesh_surface, surface,
                                          **options)
            bar.step(chosen.method + ": " + chosen.choice)
    except Cancelled as e:  # the recompute then marks the next stage cancelled, keeping the objects
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: {}: {}\n".format(label, e))
        return None
    except core.Error as e:
        import FreeCAD
        FreeCAD.Console.PrintLog("HexDom: {}: no choice of mesh ({}); recomputing with the "
                                 "defaults\n".format(label, e))
        return None
    if mesh is not None and hasattr(mesh, "PolycubeNote"):
        if mesh.PolycubeNote != chosen.polycube_note:
            mesh.PolycubeNote = chosen.polycube_note
    if chosen.method == "overlay":
        if mesh is not None:
            use_overlay(objs)
        return chosen
    if mesh is not None and poly is not None and getattr(mesh, "Polycube", poly) is None:
        mesh.Polycube = poly  # chosen again after the overlay was kept: the polycube's once more
        try:
            mesh.setExpression("Level", poly.Name + ".Level")
        except (AttributeError, RuntimeError, ValueError):
            pass
    factor = getattr(chosen, "tessellation_factor", 1.0)
    if factor != 1.0:  # the mesh is the one of another tessellation: the Surface makes that one
        surface_obj.Size = factor * float(surface_obj.Size.Value)
        surface_obj.Deflection = factor * float(surface_obj.Deflection.Value)
    if seg.EdgeWeight != chosen.edge_weight:
        seg.EdgeWeight = chosen.edge_weight
    for name, value in (("KeepWidths", chosen.keep_widths),
                        ("TetApexes", chosen.collapse_apexes), ("Level", chosen.level)):
        if poly is not None and getattr(poly, name) != value:
            setattr(poly, name, value)
    return chosen


def check_mesh_part(objs, allow_inverted=False):
    """Raises MeshPartError for the first of mesh_part's objects that failed (naming its stage
    and the core's message), or when the mesh has inverted cells (unless ``allow_inverted``).
    A Polycube the Mesh does not use (the overlay grid made it) is not checked: it may fail, it is
    kept for editing."""
    for key, stage in MESH_PART_STAGES:
        obj = objs.get(key)
        if obj is None:
            continue
        if key == "polycube" and getattr(objs.get("mesh"), "Polycube", obj) != obj:
            continue
        state = obj.State
        if "Invalid" in state or "Error" in state or "Touched" in state:
            message = obj.getStatusString() if hasattr(obj, "getStatusString") else ""
            if not message or message == "Touched":
                message = "not computed"
            raise MeshPartError("{} failed at {} ({}): {}".format(
                objs["mesh"].Label.rsplit("_mesh", 1)[0], stage, obj.Label, message),
                stage, objs)
    mesh = objs["mesh"]
    if mesh.InvertedCount and not allow_inverted and getattr(mesh, "MeshingPath", "") == "overlay":
        raise MeshPartError(
            "{}: {} inverted cells remain in the overlay grid's mesh (worst hex SJ {:.3f}); the "
            "objects are kept".format(mesh.Label, mesh.InvertedCount, mesh.MinHexSJ), "mesh", objs)
    if mesh.InvertedCount and not allow_inverted:
        raise MeshPartError(
            "{}: {} inverted cells remain after improvement (worst hex SJ {:.3f}); the "
            "objects are kept: edit the Segmentation (Edit Patches) or switch the Polycube to "
            "Manual and edit it (Build Polycube)".format(mesh.Label, mesh.InvertedCount,
                                                         mesh.MinHexSJ), "mesh", objs)
    return objs


def mesh_part(doc, part, size=0.0, level=1, improve=True, recompute=True, allow_inverted=False,
              method="auto"):
    """Meshes the Part solid ``part`` with no manual step, as `hexdom mesh` does, keeping every
    stage as an editable document object: HexDom Surface (tessellation at ``size``, 0: bounding-box
    diagonal / 30), Segmentation (automatic), Polycube (Mode Automatic: blocks of size * 2^level)
    and Mesh (generated at ``level`` and improved if ``improve``; its Level follows the Polycube's).
    Before the recompute, choose_mesh_part makes `hexdom mesh`'s choice on the Surface's triangles
    (edge weight, widths of holes, tet or hex blocks at apexes, level ``level`` or one less) and
    sets it on the Segmentation and the Polycube, so that the Mesh is the one it kept.
    ``method`` (the Mesh's Method): "auto" (the core's choice between the polycube and the
    overlay grid; when it keeps the overlay, the Mesh stops using the Polycube, which stays in the
    document), "polycube" or "overlay" (no Polycube made). The Mesh's MeshingPath says which path
    made it, its PolycubeNote why the overlay was tried.
    Returns a dict with keys surface, segmentation, polycube (not with "overlay"), mesh.

    With ``recompute`` the document is recomputed; a stage that fails raises MeshPartError naming
    the stage and the core's message (which names the charts or corners at fault), with the
    objects kept in the document (``error.objects``); so do inverted cells left in the mesh,
    unless ``allow_inverted``.
    """
    objs = make_mesh_part(doc, part, size=size, level=level, improve=improve, method=method)
    if recompute:
        with Progress("Meshing " + part.Label, 2) as bar:
            chosen = choose_mesh_part(objs)
            bar.step("chosen: " + (chosen.method + ", " + chosen.choice if chosen else "none"))
            doc.recompute()
            bar.step("recomputed")
        check_mesh_part(objs, allow_inverted)
        if chosen is not None:
            check_choice(objs, chosen)
    return objs


def check_choice(objs, chosen):
    """Warns (FreeCAD's report view) when the recomputed Mesh of mesh_part is not the mesh the
    choice produced (other element counts): the objects did not rebuild the kept candidate."""
    mesh = objs["mesh"]
    got = (mesh.HexCount, mesh.PrismCount, mesh.TetCount)
    want = tuple(chosen.mesh.count(t) for t in (core.HEX, core.WEDGE, core.TET))
    if got != want:
        import FreeCAD
        FreeCAD.Console.PrintWarning(
            "HexDom: {}: {} hex, {} prism, {} tet, but the choice ({}) gave {} hex, {} prism, "
            "{} tet\n".format(mesh.Label, *got, chosen.choice, *want))
    return got == want
