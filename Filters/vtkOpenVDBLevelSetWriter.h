/**
 * @class   vtkOpenVDBLevelSetWriter
 * @brief   Writes vtkSparseDistanceField's narrow band as an OpenVDB level set (.vdb).
 *
 * Input 0: the pieces of vtkSparseDistanceField (a vtkPartitionedDataSet of images with
 * `Distance`, the ghost array hiding the samples beyond the band, and the field data
 * `BandWidth`); input 1 (optional, SetSidesConnection): its sides, which sign the voxels
 * beyond the band (without them every such voxel outside). The file holds a FloatGrid
 * named GridName (default "surface") of class level set: its voxel (i, j, k) is the
 * grid's sample (i, j, k) (the transform's voxel size the spacing, its translation the
 * grid's origin), the band's samples its active voxels with their signed distances in
 * world units, every other voxel and tile inactive at plus or minus the background, the
 * band's half-width: inside negative, as Houdini, Blender and OpenVDB's own tools expect.
 * With a `ClosestPoint` array on the pieces, a Vec3SGrid "closest_point" of the same
 * voxels goes beside it.
 *
 * A grid whose spacings differ (a voxel is a cube), pieces without the arrays or the
 * field data above, and a file that cannot be written are errors (an ErrorEvent and a
 * non-zero GetErrorCode()); nothing is written then. Built where OpenVDB is
 * (DF_USE_OPENVDB: Debian's libopenvdb-dev).
 */
#ifndef vtkOpenVDBLevelSetWriter_h
#define vtkOpenVDBLevelSetWriter_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkWriter.h"

#include <string> // For the grid's name

class VTKDISTANCEFIELDS_EXPORT vtkOpenVDBLevelSetWriter : public vtkWriter
{
public:
  static vtkOpenVDBLevelSetWriter* New();
  vtkTypeMacro(vtkOpenVDBLevelSetWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The .vdb file to write.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  /// The level set's name in the file (default "surface").
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);

  /// The sides (vtkSparseDistanceField's output 1).
  void SetSidesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSidesData(vtkDataObject* sides) { this->SetInputData(1, sides); }

  /// What the last write put in the file: the active voxels (the band's samples, each
  /// once) and the leaf nodes of 8^3 voxels.
  vtkGetMacro(LastActiveVoxels, vtkTypeInt64);
  vtkGetMacro(LastLeafNodes, vtkTypeInt64);

protected:
  vtkOpenVDBLevelSetWriter();
  ~vtkOpenVDBLevelSetWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string GridName = "surface";
  vtkTypeInt64 LastActiveVoxels = 0;
  vtkTypeInt64 LastLeafNodes = 0;

private:
  vtkOpenVDBLevelSetWriter(const vtkOpenVDBLevelSetWriter&) = delete;
  void operator=(const vtkOpenVDBLevelSetWriter&) = delete;
};

#endif
