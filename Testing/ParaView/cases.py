"""The cases run both through the ParaView plugin (paraview.simple) and through the
system-VTK build's Python package, whose outputs must be equal bit for bit.

A case names a filter by its proxy name (the class name without "vtk"), its inputs by
property name (a file of Testing/Data, or "case:port" for an earlier case's output), its
properties by their C++ names (enumerations by the words of their SetXToY() methods) and
the output ports it writes, with their file extensions; distributed=False keeps a case
out of the comparison of one process with several (run_in_paraview.py distributed)."""

CASES = [
    dict(name="linfac_pseudonormal", filter="LinearFactorDistanceField",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=24, SignMode="PseudoNormal", Backend="CPU",
                         ComputeClosestFeature=1, ComputeClosestPoint=1),
         outputs={0: "vti"}),
    # Not in the distributed comparison: the GPU scan works relative to the requested
    # extent (its first sample, its size, its culling blocks), so on a slab a few
    # near-ties between sites resolve otherwise than on the whole grid (4 of 3840
    # samples here, distances apart by 4e-7 relative).
    dict(name="linfac_winding_gpu", filter="LinearFactorDistanceField",
         inputs={"Input": "aneurysm.vtp"},
         properties=dict(Resolution=16, SignMode="WindingNumber", Backend="GPU",
                         ComputeWindingNumber=1, ComputeClosestPoint=1),
         outputs={0: "vti"}, distributed=False),
    dict(name="linfac_explicit", filter="LinearFactorDistanceField",
         inputs={"Input": "trefoil_knot.vtp"},
         properties=dict(ExplicitGrid=1, GridOrigin=[-0.6, -0.6, -0.3],
                         GridSpacing=[0.05, 0.06, 0.07], GridDimensions=[25, 21, 9],
                         Culling="NonManifold", MaximumDistance=0.2, Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="voxelizer", filter="PolyDataVoxelizer",
         inputs={"Input": "cow.vtp"},
         properties=dict(Resolution=40, Mode="Both", Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="voxelizer_gpu", filter="PolyDataVoxelizer",
         inputs={"Input": "cow.vtp"},
         properties=dict(Resolution=40, Mode="Both", Backend="GPU"),
         outputs={0: "vti"}),
    dict(name="chamfer", filter="ChamferVoxelDistance",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=32, Metric="Manhattan", Signed=1, OutputMasks=1,
                         Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="chamfer_of_masks", filter="ChamferVoxelDistance",
         inputs={"Input": "voxelizer:0"},
         properties=dict(Metric="Chessboard26", MaximumLayers=5, Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="medial", filter="MedialAxisFilter",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=24, SeparationAngle=60, Backend="CPU"),
         outputs={0: "vti", 1: "vtp"}),
    dict(name="medial_of_field", filter="MedialAxisFilter",
         inputs={"Input": "linfac_pseudonormal:0"},
         properties=dict(Region="Both", Backend="CPU"),
         outputs={0: "vti", 1: "vtp"}),
    dict(name="segmented", filter="SegmentedDistanceField",
         inputs={"Input": "teapot.vtp"},
         properties=dict(Resolution=20, Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="contour", filter="SegmentedDistanceContour",
         inputs={"Input": "segmented:0"},
         properties=dict(FeatureAngle=40),
         outputs={0: "vtp"}),
    dict(name="blend", filter="DistanceFieldBlend",
         inputs={"Input": "segmented:0", "Target": "segmented:0"},
         properties=dict(T=0.3),
         outputs={0: "vti"}),
    dict(name="union", filter="UnionClosestPoint",
         inputs={"Input": "hubo_ankle_convex4.vtp"},
         properties=dict(QueryPoint=[0.0, 0.01, 0.01], Backend="CPU"),
         outputs={0: "vtp"}),
    dict(name="union_queries", filter="UnionClosestPoint",
         inputs={"Input": "hubo_ankle_convex4.vtp", "Query": "cow.vtp"},
         properties=dict(Backend="CPU"),
         outputs={0: "vtp"}),
    dict(name="penetration", filter="PenetrationDepth",
         inputs={"SolidP": "hubo_ankle_convex4.vtp", "SolidQ": "hubo_ankle_convex4.vtp"},
         properties=dict(Backend="CPU"),
         outputs={0: "vtp"}),
]

# The input port of each input property (the C++ classes take SetInputConnection(port)).
INPUT_PORTS = {"Input": 0, "Target": 1, "Query": 1, "SolidP": 0, "SolidQ": 1}
