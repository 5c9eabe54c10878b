// vtkDistanceFieldPartitions: the whole mesh when the input is partitioned across the
// ranks of a distributed run (vtkMultiProcessController's global controller: ParaView's
// MPI engine, or a vtkMPIController of a VTK program). A field at any sample depends on
// every cell, and ids, tie-breaks and pseudonormals on the cells' and points' order, so
// every rank needs the same whole mesh in the same order. Private to the module.
#ifndef vtkDistanceFieldPartitions_h
#define vtkDistanceFieldPartitions_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <string>
#include <vector>

class vtkImageData;
class vtkPolyData;

namespace vtkdf
{

/// The mesh a filter works on.
struct WholeMesh
{
  /// The input itself, or the ordered (and, if it was partitioned, gathered) mesh.
  vtkSmartPointer<vtkPolyData> Mesh;
  /// Empty: cell i of Mesh is input cell i. Else cell i of Mesh has global id
  /// CellIds[i] (what ClosestCellId reports).
  std::vector<vtkIdType> CellIds;
  /// How many ranks held a part of the mesh (1 when it was whole on every rank).
  int Parts = 1;
};

/// The piece of a mesh input this process asks for: the whole mesh (piece 0 of 1) when
/// it runs alone; in a distributed run its own piece (its rank of the global controller's
/// ranks, what ParaView's pipeline asks anyway, so that distributed filters upstream run
/// alike on every rank), which AssembleWholeMesh then gathers.
void MeshPiece(int& piece, int& pieces);

/// Whether every rank of a distributed run holds the same mesh (true when the process
/// runs alone). Collective.
bool SameMeshOnEveryRank(vtkPolyData* mesh);

/// Whether both meshes of a two-mesh filter (`noun` "Model" or "Mesh": its word for
/// them) are the same on every rank (SameMeshOnEveryRank, collective; a null mesh is
/// skipped); false, with `error` naming the first that is not.
bool BothMeshesOnEveryRank(vtkPolyData* const meshes[2], const char* noun, std::string& error);

/// Whether this process is rank 0 of the global controller (or runs alone): where an
/// answer that is not a piece of a grid is output, so that the ranks' outputs do not
/// repeat it.
bool IsFirstRank();

/// The whole mesh from `input`, this rank's piece. Collective: every rank of the global
/// controller must call it (from the same pipeline pass). When the ranks' pieces differ,
/// they are gathered on every rank; a mesh with global point and cell ids (the point and
/// cell data's GlobalIds attributes) is taken in global-id order, points of one id merged
/// and cells of one id kept once, so that one process and any number of ranks see the
/// same mesh. Without global ids, a mesh held by one rank alone (a reader of a
/// one-piece file gives the other ranks nothing) is that rank's mesh. False, with
/// `error`, when several ranks hold different pieces without global ids.
bool AssembleWholeMesh(vtkPolyData* input, WholeMesh& whole, std::string& error);

/// The whole image on rank 0 from every rank's piece of it (`piece`, this rank's, may be
/// empty or overlap the others: shared samples are equal), for a filter whose answer
/// needs the whole grid but is output once, by rank 0. Only the point-data arrays named
/// in `arrays` travel (those the piece has), and the field data (the first piece's). Collective:
/// every rank of the global controller must call it. Rank 0 gets the image over
/// `wholeExtent` in `whole` (false, with `error`, when the pieces leave samples out);
/// the other ranks get null and true; with `everyRank`, every rank gets the whole image.
/// One process: `whole` is `piece`.
bool GatherWholeImage(vtkImageData* piece,
  const int wholeExtent[6],
  const std::vector<std::string>& arrays,
  vtkSmartPointer<vtkImageData>& whole,
  std::string& error,
  bool everyRank = false);

} // namespace vtkdf

#endif
