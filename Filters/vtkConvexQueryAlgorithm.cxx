#include "vtkConvexQueryAlgorithm.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "GL/HeadlessGL.h"
#include "vtkConvexPieces.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

static_assert(vtkdf::SameBackendValues<vtkConvexQueryAlgorithm>(),
  "Backend values differ from BackendChoice");

int vtkConvexQueryAlgorithm::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkConvexQueryAlgorithm::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return this->CheckProperties() ? 1 : 0;
}

bool vtkConvexQueryAlgorithm::CheckProperties()
{
  std::string error;
  if (!vtkdf::enums::Backend.Check(this->Backend, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

bool vtkConvexQueryAlgorithm::ChooseBackend(vtkdf::FilterRun& run)
{
  if (!run.ResolveBackend(this->Backend))
  {
    return false;
  }
  this->LastBackend = run.Context() ? BACKEND_GPU : BACKEND_CPU;
  return true;
}

int vtkConvexQueryAlgorithm::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  for (int port = 0; port < this->GetNumberOfInputPorts(); ++port)
  {
    vtkInformation* in = inputVector[port]->GetInformationObject(0);
    if (!in)
    {
      continue;
    }
    vtkdf::RequestWholeInput(in);
    if (this->IsQueryPort(port))
    {
      int piece = 0, pieces = 1;
      vtkdf::MeshPiece(piece, pieces);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), piece);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), pieces);
    }
  }
  return 1;
}

bool vtkConvexQueryAlgorithm::ReadPieces(vtkDataObject* input,
  const char* solid,
  int port,
  vtkdf::ConvexPieceInput& pieces)
{
  std::string error;
  vtkPolyData* mesh = vtkPolyData::SafeDownCast(input);
  if (mesh && !vtkdf::SameMeshOnEveryRank(mesh))
  {
    error = "The pieces differ between the ranks of this distributed run (the mesh was "
            "partitioned upstream): every rank needs every piece";
    if (solid)
    {
      vtkErrorMacro("Solid " << solid << " (input " << port << "): " << error << ".");
    }
    else
    {
      vtkErrorMacro(<< error << ".");
    }
    return false;
  }
  if (!pieces.Read(input, this->PieceArray, this->UseConvexHulls, error))
  {
    if (solid)
    {
      vtkErrorMacro("Solid " << solid << " (input " << port << "): " << error);
    }
    else
    {
      vtkErrorMacro(<< error);
    }
    return false;
  }
  if (pieces.Hulls > 0)
  {
    vtkWarningMacro("UseConvexHulls: " << pieces.Hulls << " of " << pieces.Pieces.size()
                                       << " pieces"
                                       << (solid ? std::string(" of solid ") + solid : "")
                                       << " were not closed and convex and were replaced by "
                                          "their convex hulls.");
  }
  return true;
}

void vtkConvexQueryAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PieceArray: " << (this->PieceArray.empty() ? "(none)" : this->PieceArray)
     << "\n";
  os << indent << "UseConvexHulls: " << this->UseConvexHulls << "\n";
  os << indent << "Backend: " << vtkdf::enums::Backend.Name(this->Backend) << "\n";
  os << indent << "LastBackend: " << this->LastBackend << "\n";
  os << indent << "LastFacesVisited: " << this->LastFacesVisited << "\n";
}
