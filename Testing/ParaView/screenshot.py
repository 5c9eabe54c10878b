"""ParaView render views for the render tests (pvbatch, pvpython): a plain white one, its
screenshot as numbers, and the check of a red surface drawn on it."""
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


def red_on_white(rgb, label):
    """Whether a red (lit) surface on white covers a plausible share of the pixels (10 to
    70 %), its pixels mostly red, the corners white; prints what it found."""
    white = (rgb >= 250).all(axis=2)
    red = (rgb[:, :, 0] > rgb[:, :, 1] + 40) & (rgb[:, :, 0] > rgb[:, :, 2] + 40)
    covered = (~white).mean()
    corners = all([white[0, 0], white[0, -1], white[-1, 0], white[-1, -1]])
    print(f"{label}: {covered:.1%} of the pixels covered, "
          f"{red.sum() / max(1, (~white).sum()):.1%} of them red, corners white: {corners}")
    return 0.1 <= covered <= 0.7 and red.sum() >= 0.8 * (~white).sum() and corners
