"""The cases run both through the ParaView plugin (paraview.simple) and through the
system-VTK build's Python package, whose outputs must be equal bit for bit.

A case names a filter by its proxy name (the class name without "vtk"), its inputs by
property name (a file of Testing/Data, or "case:port" for an earlier case's output), its
properties by their C++ names (enumerations by the words of their SetXToY() methods) and
the output ports it writes, with their file extensions. "partitioned:FILE" is the file
partitioned across the ranks by ParaView, "ghosted:FILE" the same with a layer of ghost
cells (distributed_only: such cases run only in run_in_paraview.py's distributed mode;
serial_only: never there). pieces_port: an output port of pieces (a
vtkPartitionedDataSet) that a distributed run splits among the ranks: check_distributed.py
compares the ranks' pieces with one rank's."""

CASES = [
    dict(name="linfac_pseudonormal", filter="LinearFactorDistanceField",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=24, SignMode="PseudoNormal", Backend="CPU",
                         ComputeClosestFeature=1, ComputeClosestPoint=1),
         outputs={0: "vti"}),
    dict(name="linfac_winding_gpu", filter="LinearFactorDistanceField",
         inputs={"Input": "aneurysm.vtp"},
         properties=dict(Resolution=16, SignMode="WindingNumber", Backend="GPU",
                         ComputeWindingNumber=1, ComputeClosestPoint=1),
         outputs={0: "vti"}),
    dict(name="linfac_explicit", filter="LinearFactorDistanceField",
         inputs={"Input": "trefoil_knot.vtp"},
         properties=dict(ExplicitGrid=1, GridOrigin=[-0.6, -0.6, -0.3],
                         GridSpacing=[0.05, 0.06, 0.07], GridDimensions=[25, 21, 9],
                         DomainShape="NonManifold", MaximumDistance=0.2, Backend="CPU"),
         outputs={0: "vti"}),
    # The mesh partitioned across the ranks (ids generated while it is whole on rank 0,
    # then RedistributeDataSet): gathered and put in global-id order on every rank.
    dict(name="linfac_partitioned", filter="LinearFactorDistanceField",
         inputs={"Input": "partitioned:bunny_small.vtp"},
         properties=dict(Resolution=24, SignMode="WindingNumber", Backend="CPU",
                         ComputeClosestPoint=1),
         outputs={0: "vti"}, distributed_only=True),
    dict(name="segmented_partitioned", filter="SegmentedDistanceField",
         inputs={"Input": "partitioned:teapot.vtp"},
         properties=dict(Resolution=20, Backend="CPU"),
         outputs={0: "vti"}, distributed_only=True),
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
    dict(name="proximity", filter="DistanceFieldProximity",
         inputs={"Source": "bunny_small.vtp", "Target": "teapot.vtp"},
         properties=dict(Resolution=48, SignMode="WindingNumber", ContactMargin=0.5),
         outputs={0: "vtp", 1: "vtp", 2: "vtp", 3: "vtp"}),
    dict(name="mesh_distance", filter="MeshDistanceFilter",
         inputs={"Input": "teapot.vtp", "Surface": "bunny_small.vtp"},
         properties=dict(SignMode="WindingNumber", ComputeWindingNumber=1,
                         ComputeClosestFeature=1),
         outputs={0: "vtp"}),
    # The points partitioned across the ranks, each point that several ranks hold a
    # ghost but on one (the surface whole on each): every point's answer and the
    # statistics over all of them as one process computes them.
    dict(name="mesh_distance_partitioned", filter="MeshDistanceFilter",
         inputs={"Input": "ghosted:teapot.vtp", "Surface": "bunny_small.vtp"},
         properties=dict(SignMode="WindingNumber"),
         outputs={0: "vtp"}, distributed_only=True),
    # A grid (a field's of floats alone, in slabs across the ranks) clipped inside the
    # bunny: VTK's clip interpolates the input's arrays, whose integers it rounds
    # differently from one version to the next.
    dict(name="clip_grid", filter="LinearFactorDistanceField",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=20, ComputeClosestCellId=0, Backend="CPU"),
         outputs={0: "vti"}),
    dict(name="clip", filter="ClipByMeshDistance",
         inputs={"Input": "clip_grid:0", "Surface": "bunny_small.vtp"},
         properties=dict(Value=0.25),
         outputs={0: "vtu"}),
    # The sparse band's sides (port 1) and, distributed, its pieces (port 0, a
    # vtkPartitionedDataSet: each rank's share of the bricks, digested; checked against
    # the dense field in the module's own tests).
    dict(name="sparse", filter="SparseDistanceField",
         inputs={"Input": "bunny_small.vtp"},
         properties=dict(Resolution=40, BandWidth=2, BrickSize=8, SignMode="PseudoNormal"),
         outputs={1: "vti"}, pieces_port=0),
    dict(name="sparse_winding", filter="SparseDistanceField",
         inputs={"Input": "aneurysm.vtp"},
         properties=dict(Resolution=48, BandWidth=1.5, BrickSize=4, SignMode="WindingNumber",
                         ComputeClosestPoint=1),
         outputs={1: "vti"}, pieces_port=0),
    dict(name="hausdorff", filter="MeshHausdorffDistance",
         inputs={"Input": "bunny_small.vtp", "MeshB": "teapot.vtp"},
         properties=dict(RelativeError=1e-5),
         outputs={0: "vtp", 1: "vtp"}),
]

# The input port of each input property (the C++ classes take SetInputConnection(port)).
INPUT_PORTS = {"Input": 0, "Source": 0, "Target": 1, "Query": 1, "SolidP": 0, "SolidQ": 1,
               "Surface": 1, "MeshB": 1}
