"""ParaView render views for the render tests (pvbatch, pvpython): a plain white one, and
its screenshot as numbers."""
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def white_view(size=(320, 320)):
    """A render view of `size` pixels on white, without the orientation axes (the
    background then counts as "not drawn")."""
    view = simple.CreateView("RenderView")
    view.ViewSize = list(size)
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0  # ParaView 5.10 and later
    except AttributeError:
        pass
    return view


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
