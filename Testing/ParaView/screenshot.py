"""A ParaView view's screenshot as numbers, for the render tests run by pvbatch."""
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def picture(view, path, size=(320, 320)):
    """Saves `view` to `path` (PNG) and returns its pixels as a height x width x 3 array
    of ints (row 0 at the bottom, as VTK reads it)."""
    simple.SaveScreenshot(path, view, ImageResolution=list(size))
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int)
    return rgb.reshape(height, width, 3)
