/**
 * @class   vtkClipByMeshDistance
 * @brief   Clips any dataset where the exact (signed) distance to a polygon mesh crosses a
 * value: a volume mesh cut to a surface, or to a shell around it.
 *
 * Input 0 is the dataset to clip (an unstructured, structured or rectilinear grid, an
 * image, a surface); input 1 (the surface) a vtkPolyData, open, non-manifold or a soup.
 * The distance at every point of input 0 is vtkMeshDistanceFilter's (`SignMode`, by
 * default WindingNumber: negative inside, certified even on open meshes and soups), and
 * VTK's vtkTableBasedClipDataSet cuts the cells where it crosses `Value`, interpolating
 * along their edges. With InsideOut on (the default) the output keeps where the distance
 * is below Value: the part of the dataset inside the surface for Value 0, a shell of
 * thickness Value around it with SignMode Unsigned. The output is a vtkUnstructuredGrid
 * with input 0's point and cell data and the `Distance` point array, its points in double
 * precision.
 *
 * The same cut as vtkTableBasedClipDataSet with a vtkMeshDistanceFunction as its clip
 * function, in one step (the distances of all points in parallel) and with two inputs,
 * as ParaView's "Clip By Mesh Distance" uses it. The surface's hierarchy is kept while
 * the surface and SignMode do not change, so a new Value or new points reuse it.
 *
 * In a distributed run (the global controller's ranks, ParaView's MPI engine) each rank
 * clips its own piece of input 0 against the whole surface; like vtkMeshDistanceFilter
 * it is collective: every rank must execute it.
 */
#ifndef vtkClipByMeshDistance_h
#define vtkClipByMeshDistance_h

#include "vtkDistanceFieldUnstructuredGridAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkNew.h"                  // For the distances' filter

class vtkMeshDistanceFilter;

class VTKDISTANCEFIELDS_EXPORT vtkClipByMeshDistance
  : public vtkDistanceFieldUnstructuredGridAlgorithm
{
public:
  static vtkClipByMeshDistance* New();
  vtkTypeMacro(vtkClipByMeshDistance, vtkDistanceFieldUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The surface the distances are measured to (input 1); input 0 is the dataset to clip.
  void SetSurfaceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSurfaceData(vtkDataObject* data) { this->SetInputData(1, data); }

  /// How Distance is signed: vtkMeshDistanceFilter's SignMode values (0 Unsigned,
  /// 1 PseudoNormal, 2 WindingNumber, the default).
  enum SignModeType
  {
    UNSIGNED = 0,
    PSEUDO_NORMAL = 1,
    WINDING_NUMBER = 2
  };
  ///@{
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToUnsigned() { this->SetSignMode(UNSIGNED); }
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }
  ///@}

  ///@{
  /// The distance where the cut lies (world units; default 0). Finite.
  vtkSetMacro(Value, double);
  vtkGetMacro(Value, double);
  ///@}

  ///@{
  /// On (the default): keep where the distance is below Value; off: above it.
  vtkSetMacro(InsideOut, bool);
  vtkGetMacro(InsideOut, bool);
  vtkBooleanMacro(InsideOut, bool);
  ///@}

  /// Whether the last run built the surface's hierarchy (false: reused).
  bool GetLastBuiltHierarchy() const;

protected:
  vtkClipByMeshDistance();
  ~vtkClipByMeshDistance() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties();

  int SignMode = WINDING_NUMBER;
  double Value = 0;
  bool InsideOut = true;

private:
  // Kept between runs: it keeps the surface's hierarchy.
  vtkNew<vtkMeshDistanceFilter> Distances;

  vtkClipByMeshDistance(const vtkClipByMeshDistance&) = delete;
  void operator=(const vtkClipByMeshDistance&) = delete;
};

#endif
