"""Renders the boundary of a volume mesh (.vtu / .vtk) with its cell edges to a PNG, for the README's
pictures. Needs python3-vtk9 and a display (xvfb-run works).

Run: xvfb-run -a /usr/bin/python3 scripts/render_mesh.py MESH.vtu OUT.png [--azimuth DEG] [--elevation DEG]
"""

import argparse

import vtk


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("mesh")
    p.add_argument("png")
    p.add_argument("--azimuth", type=float, default=30)
    p.add_argument("--elevation", type=float, default=25)
    p.add_argument("--size", type=int, nargs=2, default=(900, 600))
    a = p.parse_args()
    reader = vtk.vtkXMLUnstructuredGridReader() if a.mesh.endswith(".vtu") else vtk.vtkUnstructuredGridReader()
    reader.SetFileName(a.mesh)
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputConnection(reader.GetOutputPort())
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(0.55, 0.72, 0.90)
    prop.EdgeVisibilityOn()
    prop.SetEdgeColor(0.1, 0.1, 0.25)
    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(1, 1, 1)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Azimuth(a.azimuth)
    camera.Elevation(a.elevation)
    renderer.ResetCamera()
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(*a.size)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(a.png)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


if __name__ == "__main__":
    main()
