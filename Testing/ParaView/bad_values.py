"""Bad values set from paraview.simple (run by check_bad_values.py under pvbatch): each
prints what the client saw; the filters' own errors go to the log."""
import math
import sys

from paraview import simple

plugin, mesh_file = sys.argv[1:3]
simple.LoadPlugin(plugin, remote=True)
mesh = simple.XMLPolyDataReader(FileName=[mesh_file])


def points(proxy):
    proxy.UpdatePipeline()
    return proxy.GetDataInformation().GetNumberOfPoints()


nan_spacing = simple.LinearFactorDistanceField(
    Input=mesh, ExplicitGrid=1, GridSpacing=[math.nan, 1, 1], Backend="CPU")
print(f"nan spacing: {points(nan_spacing)} points")
no_resolution = simple.ChamferVoxelDistance(Input=mesh, Resolution=0, Backend="CPU")
print(f"resolution 0: {points(no_resolution)} points")
try:
    simple.LinearFactorDistanceField(Input=mesh, SignMode="Bogus")
    print("unknown name: accepted")
except ValueError as error:
    print(f"unknown name: ValueError ({error})")
out_of_list = simple.LinearFactorDistanceField(Input=mesh, Resolution=8, Backend="CPU")
out_of_list.GetProperty("SignMode").SetData(7)
print(f"SignMode 7: {points(out_of_list)} points")
# The same filter once the value is right again: the error does not stick.
out_of_list.GetProperty("SignMode").SetData(1)
print(f"SignMode 1: {points(out_of_list)} points")
