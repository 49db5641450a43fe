"""FEM set-up without GUI: puts HexDom meshes into FEM analyses."""


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
    return mesh_obj
