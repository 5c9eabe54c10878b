// Subcommands: vtkdf's subcommands, one file each; each takes main's arguments
// (argv[1] is its name) and returns the exit status.
#ifndef vtkdf_Subcommands_h
#define vtkdf_Subcommands_h

#include <string>

class vtkPolyData;

namespace vtkdf::cli
{
struct CommonOptions;

/// vtkdf linfac (vtkLinearFactorDistanceField; vtkSparseDistanceField with --band K and
/// a .vtpd output).
int Linfac(int argc, char* argv[]);
/// What vtkdf linfac --band ... -o OUT.vtpd passes on to vtkSparseDistanceField.
struct SparseOptions
{
  double BandWidth = 0;
  int BrickSize = 32;
  int DomainShape = 0;
  int SignMode = 0; // vtkSparseDistanceField's
  std::string Arrays, Sides;
  std::string Vdb; // an OpenVDB level set (vtkOpenVDBLevelSetWriter) to write as well
};
/// vtkdf linfac's sparse band: the pieces to the output (.vtpd) or a level set to it
/// (.vdb), the sides to `Sides` and a level set to `Vdb` (both optional).
int LinfacSparse(vtkPolyData* mesh, CommonOptions& common, const SparseOptions& options);
/// vtkdf voxelize (vtkPolyDataVoxelizer).
int Voxelize(int argc, char* argv[]);
/// vtkdf chamfer (vtkChamferVoxelDistance).
int Chamfer(int argc, char* argv[]);
/// vtkdf medial (vtkMedialAxisFilter).
int Medial(int argc, char* argv[]);
/// vtkdf segment (vtkSegmentedDistanceField).
int Segment(int argc, char* argv[]);
/// vtkdf blend (vtkDistanceFieldBlend).
int Blend(int argc, char* argv[]);
/// vtkdf union (vtkUnionClosestPoint).
int Union(int argc, char* argv[]);
/// vtkdf pd (vtkPenetrationDepth).
int PenetrationDepth(int argc, char* argv[]);
/// vtkdf proximity (vtkDistanceFieldProximity).
int Proximity(int argc, char* argv[]);
/// vtkdf probe (vtkMeshDistanceFilter).
int Probe(int argc, char* argv[]);
/// vtkdf hausdorff (vtkMeshHausdorffDistance).
int Hausdorff(int argc, char* argv[]);
/// vtkdf clip (vtkClipByMeshDistance).
int Clip(int argc, char* argv[]);
/// vtkdf render (vtkSegmentedDistanceVolumeMapper).
int Render(int argc, char* argv[]);
} // namespace vtkdf::cli

#endif
