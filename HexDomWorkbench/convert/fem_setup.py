"""FEM set-up without GUI: puts HexDom meshes into FEM analyses."""

from . import femmesh

FACE_GROUP = "Face{}"  # the HexDom Mesh's node group of the CAD face Face<k> of the Part it meshes


def analysis_meshes(analysis):
    """FEM mesh objects inside ``analysis``."""
    return [o for o in analysis.Group if o.isDerivedFrom("Fem::FemMeshObject")]


def add_to_analysis(analysis, mesh_obj):
    """Adds the FEM mesh object ``mesh_obj`` to ``analysis``.

    Raises ValueError if the analysis already holds another mesh (CalculiX takes one) or the mesh
    sits in another group. Adding a mesh that is already there does nothing.
    """
    if not analysis.isDerivedFrom("Fem::FemAnalysis"):
        raise ValueError("{} is not a FEM analysis".format(analysis.Label))
    if not mesh_obj.isDerivedFrom("Fem::FemMeshObject"):
        raise ValueError("{} is not a FEM mesh object".format(mesh_obj.Label))
    if mesh_obj in analysis.Group:
        return mesh_obj
    others = analysis_meshes(analysis)
    if others:
        raise ValueError("analysis {} already holds the mesh {}: remove it first (the solver "
                         "takes one mesh)".format(analysis.Label, others[0].Label))
    parent = mesh_obj.getParentGroup()
    if parent is not None:
        raise ValueError("{} already belongs to {}".format(mesh_obj.Label, parent.Label))
    analysis.addObject(mesh_obj)
    add_constraint_groups(analysis, mesh_obj)
    return mesh_obj


def meshed_part(mesh_obj):
    """The Part a HexDom Mesh was made from (Segmentation -> Surface -> Source), or None."""
    seg = getattr(mesh_obj, "Segmentation", None)
    return getattr(getattr(seg, "Surface", None), "Source", None)


def constraint_groups(analysis, part, faces):
    """{"<member Name>_Nodes": sorted 0-based nodes} for each member of ``analysis`` whose References
    name faces of ``part``: the union of those faces' nodes, ``faces`` being {"Face<k>": 0-based
    nodes} (core.face_sets' node sets, or a FemMesh's Face<k> groups less one). Members on other
    objects or on edges and vertices are left out (FreeCAD's search finds their nodes)."""
    groups = {}
    if part is None or not faces:
        return groups
    for member in analysis.Group:
        nodes = set()
        for obj, subs in getattr(member, "References", []) or []:
            if obj != part:
                continue
            for sub in subs:
                nodes.update(faces.get(sub, []) if sub.startswith("Face") else [])
        if nodes:
            groups[member.Name + "_Nodes"] = sorted(int(n) for n in nodes)
    return groups


def add_constraint_groups(analysis, mesh_obj, part=None):
    """For each member of ``analysis`` whose References name faces of ``part`` (default: the Part the
    HexDom Mesh ``mesh_obj`` meshes), a node group "<member Name>_Nodes" on the mesh: the nodes of its
    faces' groups Face<k> (made when the mesh was stored; constraint_groups). FreeCAD's CalculiX
    writer takes a constraint's nodes from such a group instead of searching them by geometry, as it
    does for FemMeshGmsh's groups. Returns the names of the groups made."""
    part = part if part is not None else meshed_part(mesh_obj)
    fem = mesh_obj.FemMesh
    faces = {name: [n - 1 for n in nodes] for name, nodes in femmesh.node_groups(fem, "Face").items()}
    groups = constraint_groups(analysis, part, faces)
    if groups:
        untouched = "Touched" not in mesh_obj.State
        mesh_obj.FemMesh = femmesh.set_node_groups(fem, groups)
        if untouched:  # groups added to an up-to-date mesh leave it up to date
            mesh_obj.purgeTouched()
    return sorted(groups)
