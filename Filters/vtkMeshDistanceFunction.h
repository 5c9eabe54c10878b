/**
 * @class   vtkMeshDistanceFunction
 * @brief   The exact signed distance to a polygon mesh as an implicit function, for VTK's
 * clip, cut, extract and sample filters.
 *
 * A drop-in for vtkImplicitPolyDataDistance (SetInput, NoValue,
 * EvaluateFunctionAndGetClosestPoint) whose values are the exact distances of
 * vtkMeshDistanceFilter (the same queries: vtkMeshDistanceFilter.h), signed by SignMode:
 * the generalized winding number by default (right on open meshes, soups and meshes
 * with flipped faces, where an angle-weighted normal is not), or the pseudonormal, or
 * unsigned. So vtkClipPolyData, vtkClipDataSet, vtkTableBasedClipDataSet, vtkCutter,
 * vtkExtractGeometry and vtkSampleFunction get exact distances and certified signs with
 * no other change to a pipeline.
 *
 * EvaluateFunction(x) and EvaluateGradient(x, g) are thread-safe (VTK may call them from
 * many threads); the batch EvaluateFunction(vtkDataArray*, vtkDataArray*), which
 * FunctionValue(vtkDataArray*, vtkDataArray*) and vtkCutter's grid path call, runs
 * vtkMeshDistanceFilter's parallel path (the points in Morton order). The surface's
 * hierarchy is built at the first evaluation after the input (its modification time) or
 * SignMode changed. The gradient is vtkMeshDistanceFilter's Gradient: the unit vector
 * from the closest point, times the sign. With no input, or an input that is not a
 * valid surface (reported once with vtkErrorMacro), every value is NoValue (default 0),
 * its gradient 0 and its closest point NoClosestPoint.
 */
#ifndef vtkMeshDistanceFunction_h
#define vtkMeshDistanceFunction_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkImplicitFunction.h"
#include "vtkSmartPointer.h" // For the input

#include <atomic> // For the built flag
#include <memory> // For std::unique_ptr
#include <mutex>  // For the build

#ifndef __VTK_WRAP__
namespace vtkdf
{
class PointDistanceQueries;
struct PointAnswer;
struct PointQueryParts;
}
#endif

class vtkPolyData;

class VTKDISTANCEFIELDS_EXPORT vtkMeshDistanceFunction : public vtkImplicitFunction
{
public:
  static vtkMeshDistanceFunction* New();
  vtkTypeMacro(vtkMeshDistanceFunction, vtkImplicitFunction);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The surface: vertices, lines, polygons and strips; open, non-manifold or a soup.
  void SetInput(vtkPolyData* surface);
  vtkPolyData* GetInput();

  /// The values of vtkMeshDistanceFilter's SignMode.
  enum SignModeType
  {
    UNSIGNED = 0,
    PSEUDO_NORMAL = 1,
    WINDING_NUMBER = 2
  };
  ///@{
  /// SignMode (default WindingNumber: negative inside).
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToUnsigned() { this->SetSignMode(UNSIGNED); }
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }
  ///@}

  ///@{
  /// The value, and closest point, where there is no valid surface.
  vtkSetMacro(NoValue, double);
  vtkGetMacro(NoValue, double);
  vtkSetVector3Macro(NoClosestPoint, double);
  vtkGetVector3Macro(NoClosestPoint, double);
  ///@}

  /// Includes the input's modification time.
  vtkMTimeType GetMTime() override;

  using vtkImplicitFunction::EvaluateFunction;
  /// The signed distance at x.
  double EvaluateFunction(double x[3]) override;
  /// The distances at every point of `input` (3 components) into `output`, in parallel.
  void EvaluateFunction(vtkDataArray* input, vtkDataArray* output) override;
  /// The gradient at x: the unit vector from the closest point, times the sign.
  void EvaluateGradient(double x[3], double g[3]) override;
  /// The signed distance at x and its closest point on the surface.
  double EvaluateFunctionAndGetClosestPoint(double x[3], double closestPoint[3]);

  /// Whether the surface's hierarchy is ready for the current input and SignMode,
  /// building it if not (what the evaluations do first); false without a valid surface.
  bool Prepare();

protected:
  vtkMeshDistanceFunction();
  ~vtkMeshDistanceFunction() override;

  int SignMode = WINDING_NUMBER;
  double NoValue = 0;
  double NoClosestPoint[3] = { 0, 0, 0 };

private:
#ifndef __VTK_WRAP__
  /// One point's answer, seeded by this thread's previous one.
  void Query(const double x[3], const vtkdf::PointQueryParts& parts, vtkdf::PointAnswer& answer);
#endif
  vtkSmartPointer<vtkPolyData> Input;
#ifndef __VTK_WRAP__
  std::unique_ptr<vtkdf::PointDistanceQueries> Queries;
  std::mutex Building;
  std::atomic<vtkMTimeType> BuiltTime{ 0 }; // the input's modification time when built
  std::atomic<int> BuiltSign{ -1 };
  std::atomic<bool> Valid{ false };
  uint64_t Build = 0; // this build's number (seeds come from answers of the same build)
#endif

  vtkMeshDistanceFunction(const vtkMeshDistanceFunction&) = delete;
  void operator=(const vtkMeshDistanceFunction&) = delete;
};

#endif
