/**
 * @class   vtkSparseDistanceField
 * @brief   Exact distance field of a polygon mesh in a narrow band, stored only in the
 * bricks of the grid that the band touches.
 *
 * The field of vtkLinearFactorDistanceField (Sud, Govindaraju, Gayle and Manocha,
 * "Interactive 3D Distance Field Computation using Linear Factorization", I3D 2006) with
 * MaximumDistance = BandWidth spacings, without the dense grid: the grid (Resolution and
 * Padding, or the explicit grid, as every field of the module) is cut into bricks of
 * BrickSize samples a side, and only the bricks that hold a sample within the band are
 * computed and kept. Every sample of a brick holds the dense field's bits (the dense
 * field on its site scan, Route SiteScan).
 *
 * Output port 0, a vtkPartitionedDataSet: one vtkImageData per brick, in the global
 * grid's index space (its extent within the whole grid, the grid's origin and spacing),
 * sharing its boundary samples with its neighbours so that a contour has no cracks. Its
 * point data: `Distance` (float; +-BandWidth spacings beyond the band, negative inside
 * with SignMode PseudoNormal), optionally `ClosestCellId`, `ClosestFeature` and
 * `ClosestPoint` (vtkLinearFactorDistanceField's arrays, -1, 255 and NaN beyond the
 * band), and VTK's ghost array with HIDDENPOINT on the samples beyond the band.
 *
 * Output port 1, a vtkImageData with a cell per brick (its origin the grid's, its
 * spacing BrickSize spacings): `Side` (signed char: -1 inside, 1 outside, 0 unknown or
 * a brick of the partitioned output) and `Piece` (int: the brick's index in port 0, -1
 * when none), so that "inside?" has an answer anywhere in the grid: a sample beyond the
 * band takes its brick's Side, or its piece's sign where there is a piece.
 *
 * With SignMode PseudoNormal the sides beyond the band are flooded from the band's
 * signs, within each brick and then over the grid of bricks
 * (Filters/Core/LinearFactor/SparseBand.h): the dense field's sides wherever the band's
 * signs agree, as on a closed mesh. With SignMode WindingNumber every sample has the
 * dense field's side, open meshes and soups included: a brick beyond the band gets its
 * one side from a single test (Filters/Core/Winding/BrickWindingSigns.h), and one whose
 * samples lie on both sides (the surface |w| = 1/2 of an open mesh can pass between the
 * band's bricks) is a piece of its own, every sample hidden. The sparse band runs on the
 * CPU.
 *
 * In a distributed run (vtkMultiProcessController's global controller: ParaView's MPI
 * engine, or a vtkMPIController) every rank computes its share of the bricks: output 0
 * holds its pieces, output 1 the part of the grid of bricks it is asked for (Piece
 * numbers the pieces among all ranks' pieces); together they are one process's outputs,
 * bit for bit. Every rank must run the filter in the same pass (docs/distributed.md).
 */
#ifndef vtkSparseDistanceField_h
#define vtkSparseDistanceField_h

#include "vtkDistanceFieldAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

class VTKDISTANCEFIELDS_EXPORT vtkSparseDistanceField : public vtkDistanceFieldAlgorithm
{
public:
  static vtkSparseDistanceField* New();
  vtkTypeMacro(vtkSparseDistanceField, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How Distance is signed: Unsigned (the default), PseudoNormal (negative inside, by
  /// the angle-weighted pseudonormal of the closest feature) or WindingNumber (inside
  /// where the generalized winding number has |w| > 1/2), as vtkLinearFactorDistanceField.
  enum SignModeType
  {
    UNSIGNED = 0,
    PSEUDO_NORMAL = 1,
    WINDING_NUMBER = 2
  };
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToUnsigned() { this->SetSignMode(UNSIGNED); }
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }

  /// The sites' domains, as vtkLinearFactorDistanceField's DomainShape (0 Auto, the
  /// default; 1 NonManifold; 2 Manifold). Every mode gives the same field.
  vtkSetMacro(DomainShape, int);
  vtkGetMacro(DomainShape, int);

  /// The band's half-width in grid spacings (the smallest spacing): samples farther from
  /// the mesh are beyond the band. Default 3; finite, at least 1e-3.
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);

  /// Samples per brick along each axis (the pieces have one more, shared with the next
  /// brick). Default 32; between 2 and 1024.
  vtkSetMacro(BrickSize, int);
  vtkGetMacro(BrickSize, int);

  ///@{
  /// Which arrays to produce besides Distance (off by default).
  vtkSetMacro(ComputeClosestCellId, bool);
  vtkGetMacro(ComputeClosestCellId, bool);
  vtkBooleanMacro(ComputeClosestCellId, bool);
  vtkSetMacro(ComputeClosestFeature, bool);
  vtkGetMacro(ComputeClosestFeature, bool);
  vtkBooleanMacro(ComputeClosestFeature, bool);
  vtkSetMacro(ComputeClosestPoint, bool);
  vtkGetMacro(ComputeClosestPoint, bool);
  vtkBooleanMacro(ComputeClosestPoint, bool);
  ///@}

  /// What the last run found: the samples within the band (counted once per piece that
  /// holds them), the pieces, and the bricks that some site's band reached (the pieces
  /// and the bricks found beyond the band).
  vtkGetMacro(LastBandSamples, vtkTypeInt64);
  vtkGetMacro(LastPieces, vtkTypeInt64);
  vtkGetMacro(LastCandidateBricks, vtkTypeInt64);
  /// SignMode WindingNumber: the bricks beyond the band whose sides no single test
  /// proved, decided sample by sample, in the last run.
  vtkGetMacro(LastWindingBricksDecided, vtkTypeInt64);
  /// The bytes the last run's pieces hold, in MiB.
  vtkGetMacro(LastPieceMemory, double);

protected:
  vtkSparseDistanceField();
  ~vtkSparseDistanceField() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties() override;
  std::string PointCloudRefusal() override;

  int SignMode = UNSIGNED;
  int DomainShape = 0;
  double BandWidth = 3;
  int BrickSize = 32;
  bool ComputeClosestCellId = false;
  bool ComputeClosestFeature = false;
  bool ComputeClosestPoint = false;
  vtkTypeInt64 LastBandSamples = 0;
  vtkTypeInt64 LastPieces = 0;
  vtkTypeInt64 LastCandidateBricks = 0;
  vtkTypeInt64 LastWindingBricksDecided = 0;
  double LastPieceMemory = 0;

private:
  vtkSparseDistanceField(const vtkSparseDistanceField&) = delete;
  void operator=(const vtkSparseDistanceField&) = delete;
};

#endif
