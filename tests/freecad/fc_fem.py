"""A static CalculiX analysis through FreeCAD's FEM workbench, shared by the App tests that solve:
one steel-like material, one fixed face, one force, CalculiX run by FemToolsCcx."""

import ObjectsFem
from femtools import ccxtools


def static_analysis(doc, E, nu, fixed, loaded, force, direction, reversed=False):
    """Analysis with a CalculiX solver, a material (E in MPa, Poisson ratio nu), ConstraintFixed on
    ``fixed`` and a ConstraintForce of ``force`` N on ``loaded`` (both [(object, "FaceN")]) along
    ``direction`` ((object, ["FaceN" or "EdgeN"])). Returns (analysis, solver, force object); the
    mesh is added by the caller."""
    analysis = ObjectsFem.makeAnalysis(doc, "Analysis")
    solver = ObjectsFem.makeSolverCalculixCcxTools(doc, "Solver")
    analysis.addObject(solver)
    material = ObjectsFem.makeMaterialSolid(doc, "Steel")
    mat = material.Material
    mat.update({"Name": "Steel", "YoungsModulus": "{} MPa".format(E), "PoissonRatio": str(nu)})
    material.Material = mat
    analysis.addObject(material)
    constraint = ObjectsFem.makeConstraintFixed(doc, "ConstraintFixed")
    constraint.References = fixed
    analysis.addObject(constraint)
    load = ObjectsFem.makeConstraintForce(doc, "ConstraintForce")
    load.References = loaded
    load.Force = force
    load.Direction = direction
    load.Reversed = reversed
    analysis.addObject(load)
    return analysis, solver, load


def write_inp(analysis, solver, work_dir):
    """FemToolsCcx with its input file written in ``work_dir`` (fea.inp_file_name)."""
    fea = ccxtools.FemToolsCcx(analysis=analysis, solver=solver)
    fea.update_objects()
    fea.setup_working_dir(str(work_dir))
    assert fea.check_prerequisites() == ""
    fea.write_inp_file()
    assert fea.inp_file_name
    return fea


def solve(fea, analysis):
    """Runs CalculiX on the written input, loads its result: {node number: displacement vector}."""
    fea.setup_ccx()
    assert fea.ccx_run() == 0, fea.ccx_stdout
    fea.load_results()
    results = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")]
    assert len(results) == 1, "no CalculiX results loaded"
    return dict(zip(results[0].NodeNumbers, results[0].DisplacementVectors))
