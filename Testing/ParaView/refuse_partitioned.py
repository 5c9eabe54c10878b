"""A mesh partitioned across the ranks without global ids (ParaView's sphere source
makes a part of the sphere on each rank): the filter must refuse it with its message, on
every rank, and pvbatch go on (run under mpiexec -n 2 pvbatch --symmetric by
check_distributed.py)."""
import sys

from paraview import simple
from paraview.modules.vtkRemotingCore import vtkProcessModule

simple.LoadPlugin(sys.argv[1], remote=True)
rank = vtkProcessModule.GetProcessModule().GetPartitionId()
sphere = simple.Sphere(ThetaResolution=32, PhiResolution=16)
field = simple.LinearFactorDistanceField(Input=sphere, Resolution=16, Backend="CPU")
field.UpdatePipeline()
points = field.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
print(f"partitioned without ids: rank {rank} output has {points} points", flush=True)
