// vtkdf: the command-line front end of VTK Distance Fields. This file dispatches to the
// subcommands, one file each (Subcommands.h), over a shared option parser (Options.h).
//
//   vtkdf linfac MESH -o OUT.vti [grid] [--signed] [--sign pseudonormal|winding]
//         [--backend auto|gpu|cpu] [--domains auto|nonmanifold|manifold]
//         [--route auto|scan|queries]
//         [--arrays distance,cellid,feature,point,winding]
//         [--max-distance D] [--png SLICE.png] [--timing]
//   vtkdf voxelize MESH -o OUT.vti [--mode boundary|solid|both] [grid] [--backend ...]
//         [--timing]
//   vtkdf chamfer INPUT -o OUT.vti [--metric manhattan|chessboard18|chessboard26]
//         [--layers M] [--signed] [grid] [--backend ...] [--timing]
//   vtkdf medial INPUT -o OUT.vti [--angle THETA] [--region inside|outside|both]
//         [--sign pseudonormal|winding] [grid]
//         [--backend ...] [--points OUT.vtp] [--png SLICE.png] [--timing]
//   vtkdf segment MESH -o OUT.vti [grid] [--delta D] [--region-offset D] [--uncut]
//         [--surface OUT.vtp] [--feature-angle A] [--paper-vertices]
//   vtkdf blend A.vti B.vti -t T -o OUT.vti [--png SLICE.png]
//   vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS] [--piece-array NAME]
//         [--convex-hulls] [--backend ...] [--timing]
//   vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls] [--backend ...]
//         [--timing]
//         (penetration depth; P, Q: convex pieces in the forms union takes)
//   vtkdf proximity A B -o OUT.vtp [--contacts OUT.vtp] [--models A.vtp B.vtp]
//         [--resolution N | --spacing H] [--margin M] [--sign winding|pseudonormal]
//         [--no-contacts] [--backend ...] [--timing]
//   vtkdf probe MESH POINTS -o OUT [--signed] [--sign pseudonormal|winding]
//         [--max-distance D] [--winding] [--timing]
//   vtkdf hausdorff A B -o A_OUT.vtp [--output-b B_OUT.vtp] [--relative-error E] [--timing]
//   vtkdf clip MESH DATASET -o OUT.vtu [--value V] [--sign unsigned|pseudonormal|winding]
//         [--outside] [--timing]
//   vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H] ...
//         (vtkSegmentedDistanceVolumeMapper; needs an X server)
//
// grid: [--resolution N] [--padding F] [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ]
// MESH: .vtp .vtk .ply .stl .obj; chamfer's INPUT may also be a .vti with a Boundary mask
// (and optionally Solid), e.g. the output of vtkdf voxelize. --timing prints one line
// that scripts can read:
//   vtkdf: linfac dims=NXxNYxNZ backend=cpu renderer="cpu" time_s=0.123 ...
#include "Options.h"
#include "Subcommands.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0)
    {
      vtkdf::cli::PrintUsage(stdout);
      return 0;
    }
  }
  if (argc < 3)
  {
    return vtkdf::cli::Usage();
  }
  const std::string subcommand = argv[1];
  const std::pair<const char*, int (*)(int, char*[])> subcommands[] = { { "linfac",
                                                                          vtkdf::cli::Linfac },
    { "voxelize", vtkdf::cli::Voxelize },
    { "chamfer", vtkdf::cli::Chamfer },
    { "medial", vtkdf::cli::Medial },
    { "segment", vtkdf::cli::Segment },
    { "blend", vtkdf::cli::Blend },
    { "union", vtkdf::cli::Union },
    { "pd", vtkdf::cli::PenetrationDepth },
    { "proximity", vtkdf::cli::Proximity },
    { "probe", vtkdf::cli::Probe },
    { "hausdorff", vtkdf::cli::Hausdorff },
    { "clip", vtkdf::cli::Clip },
    { "render", vtkdf::cli::Render } };
  for (const auto& entry : subcommands)
  {
    if (subcommand == entry.first)
    {
      return entry.second(argc, argv);
    }
  }
  return vtkdf::cli::Usage(("unknown subcommand " + subcommand).c_str());
}
