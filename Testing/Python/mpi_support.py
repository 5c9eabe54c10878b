"""What the distributed tests without ParaView share: VTK's MPI controller as the global
controller, the bundled meshes, and a mesh moved rigidly."""
import os

from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller uses it)
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController


def start_controller():
    """VTK's vtkMPIController, initialized and made the global controller; with this
    process's rank and the number of ranks."""
    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    return controller, controller.GetLocalProcessId(), controller.GetNumberOfProcesses()


def read(folder, name):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(folder, name))
    reader.Update()
    return reader.GetOutput()


def moved(mesh, offset):
    """A copy of `mesh` with its points (as doubles) moved by `offset`."""
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for i in range(mesh.GetNumberOfPoints()):
        x = mesh.GetPoint(i)
        points.InsertNextPoint(x[0] + offset[0], x[1] + offset[1], x[2] + offset[2])
    out = vtkPolyData()
    out.DeepCopy(mesh)
    out.SetPoints(points)
    return out
