"""Which HexDom objects hold what Mesh Part's pipeline made (their FromPipeline property, the
Mesh's Pipeline; see part_meshing and objects/pipeline.py), and what an edit changes: an edited
input of a stage object makes its whole chain compute stage by stage (stage_edited). Reads and sets
properties only, by type name, so that every object module can use it."""

STAGE_TYPES = ("HexDom::Surface", "HexDom::Segmentation", "HexDom::Polycube")
MESH_TYPE = "HexDom::Mesh"
CHAIN_TYPES = STAGE_TYPES + (MESH_TYPE,)

_filling = [0]


class filling:
    """``with filling():`` marks the properties set inside as written by Mesh Part's pipeline
    (objects/pipeline.py), not edited by the user: the stage objects stay FromPipeline."""

    def __enter__(self):
        _filling[0] += 1
        return self

    def __exit__(self, *exc):
        _filling[0] -= 1
        return False

    @staticmethod
    def active():
        return _filling[0] > 0


def restoring(obj):
    """True while ``obj``'s document is being loaded (its properties are read, not edited)."""
    doc = getattr(obj, "Document", None)
    return bool(getattr(doc, "Restoring", False)) or "Restore" in getattr(obj, "State", ())


def type_of(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None)


def polycubes_of(seg):
    """The HexDom Polycubes built on Segmentation ``seg`` (their Segmentation links it)."""
    return [o for o in getattr(seg, "InList", []) if type_of(o) == "HexDom::Polycube"
            and getattr(o, "Segmentation", None) == seg]


def objects_of(mesh):
    """mesh_part's dict of objects for HexDom Mesh ``mesh``: its Segmentation, that one's
    Surface, and its Polycube (the Polycube built on the Segmentation when the Mesh does not
    link one: the overlay's mesh was kept); None for those missing."""
    seg = getattr(mesh, "Segmentation", None)
    poly = getattr(mesh, "Polycube", None)
    if poly is None and seg is not None:  # only one the pipeline still fills (see stage_edited)
        found = [p for p in polycubes_of(seg) if getattr(p, "FromPipeline", False)]
        poly = found[0] if found else None
    return {"surface": getattr(seg, "Surface", None), "segmentation": seg, "polycube": poly,
            "mesh": mesh}


def stages(objs):
    return [objs[k] for k in ("surface", "segmentation", "polycube") if objs.get(k) is not None]


def chain_of(obj):
    """The HexDom Surfaces, Segmentations, Polycubes and Meshes linked to ``obj`` (itself
    included), through their inputs and the objects using them."""
    seen, out, todo = set(), [], [obj]
    while todo:
        o = todo.pop()
        if o is None or type_of(o) not in CHAIN_TYPES or o.Name in seen:
            continue
        seen.add(o.Name)
        out.append(o)
        todo.extend(getattr(o, name, None) for name in ("Surface", "Segmentation", "Polycube"))
        todo.extend(getattr(o, "InList", []))
    return out


def holds_data(obj):
    t = type_of(obj)
    if t == "HexDom::Surface":
        return len(obj.Triangles) > 0
    if t == "HexDom::Segmentation":
        return len(obj.Labels) > 0
    return len(obj.BlockTypes) > 0


def stage_edited(obj):
    """An input of ``obj``, a stage object the pipeline filled (FromPipeline), was edited: every
    stage object of its chain computes as a stage from now on (FromPipeline cleared; those that
    hold the pipeline's data are not recomputed for it), so that the edit re-runs the stages after
    it and the Mesh, which then leaves Pipeline (see hex_mesh.HexMesh.generate). A Polycube no
    Mesh uses (the overlay grid's mesh was kept) leaves alone: the Mesh stays in Pipeline and no
    longer fills it."""
    with filling():
        if type_of(obj) == "HexDom::Polycube" and not any(
                type_of(m) == MESH_TYPE for m in getattr(obj, "InList", [])):
            obj.FromPipeline = False  # a Polycube no Mesh uses (the overlay's mesh was kept)
            return
        for o in chain_of(obj):
            if type_of(o) in STAGE_TYPES and getattr(o, "FromPipeline", False):
                o.FromPipeline = False
                if o is not obj and holds_data(o):
                    o.purgeTouched()
            elif type_of(o) == MESH_TYPE and o is obj:  # the Mesh's Pipeline cleared
                objs = objects_of(o)
                if objs.get("polycube") is not None and o.Polycube is objs["polycube"]:
                    follow_level(o, objs["polycube"])


def follow_level(mesh, poly):
    """The Mesh's Level an expression of the Polycube's (the blocks are made for it), or none
    (``poly`` None: the Mesh's own Level, the pipeline's option)."""
    try:
        mesh.setExpression("Level", poly.Name + ".Level" if poly is not None else None)
    except (AttributeError, RuntimeError, ValueError):
        pass
