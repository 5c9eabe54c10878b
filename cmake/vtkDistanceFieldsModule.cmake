# The module's sources (included from the generated module directory, see CMakeLists.txt).
set(df_root "${CMAKE_SOURCE_DIR}")
set(classes
  "${df_root}/Filters/vtkDistanceFieldImageAlgorithm"
  "${df_root}/Filters/vtkDistanceFieldPolyDataAlgorithm"
  "${df_root}/Filters/vtkDistanceFieldDataSetAlgorithm"
  "${df_root}/Filters/vtkDistanceFieldUnstructuredGridAlgorithm"
  "${df_root}/Filters/vtkDistanceFieldAlgorithm"
  "${df_root}/Filters/vtkLinearFactorDistanceField"
  "${df_root}/Filters/vtkPolyDataVoxelizer"
  "${df_root}/Filters/vtkChamferVoxelDistance"
  "${df_root}/Filters/vtkMedialAxisFilter"
  "${df_root}/Filters/vtkSegmentedDistanceField"
  "${df_root}/Filters/vtkDistanceFieldBlend"
  "${df_root}/Filters/vtkSegmentedDistanceContour"
  "${df_root}/Filters/vtkConvexQueryAlgorithm"
  "${df_root}/Filters/vtkUnionClosestPoint"
  "${df_root}/Filters/vtkPenetrationDepth"
  "${df_root}/Filters/vtkDistanceFieldProximity"
  "${df_root}/Filters/vtkMeshDistanceFilter"
  "${df_root}/Filters/vtkMeshDistanceFunction"
  "${df_root}/Filters/vtkMeshHausdorffDistance"
  "${df_root}/Filters/vtkClipByMeshDistance"
  "${df_root}/Filters/vtkSparseDistanceField")
# The .vdb writer, where OpenVDB is (DF_USE_OPENVDB, Filters/Core/CMakeLists.txt).
if (DF_USE_OPENVDB)
  list(APPEND classes "${df_root}/Filters/vtkOpenVDBLevelSetWriter")
endif ()
vtk_module_add_module(DistanceFields::vtkDistanceFields
  CLASSES ${classes}
  HEADERS "${df_root}/Filters/vtkDistanceFieldRunRecord.h"
  SOURCES "${df_root}/Filters/vtkDistanceFieldMeshInput.cxx"
    "${df_root}/Filters/vtkDistanceFieldArrays.cxx"
    "${df_root}/Filters/vtkDistanceFieldExecution.cxx"
    "${df_root}/Filters/vtkDistanceFieldRun.cxx"
    "${df_root}/Filters/vtkDistanceFieldEnums.cxx"
    "${df_root}/Filters/vtkConvexPieces.cxx"
    "${df_root}/Filters/vtkDistanceFieldPartitions.cxx"
  PRIVATE_HEADERS "${df_root}/Filters/vtkDistanceFieldMeshInput.h"
    "${df_root}/Filters/vtkDistanceFieldArrays.h"
    "${df_root}/Filters/vtkDistanceFieldExecution.h"
    "${df_root}/Filters/vtkDistanceFieldRun.h"
    "${df_root}/Filters/vtkDistanceFieldEnums.h"
    "${df_root}/Filters/vtkConvexPieces.h"
    "${df_root}/Filters/vtkDistanceFieldPartitions.h")
vtk_module_include(DistanceFields::vtkDistanceFields
  PUBLIC "$<BUILD_INTERFACE:${df_root}/Filters>")
# The VTK-free cores (Filters/Core), one static library per family, linked into the
# module's shared library.
vtk_module_link(DistanceFields::vtkDistanceFields PRIVATE ${DF_CORE_LIBRARIES})
# The .vdb writer loads OpenVDB's module (vtkdf_LevelSet) from the library's own folder.
if (DF_USE_OPENVDB)
  vtk_module_link(DistanceFields::vtkDistanceFields PRIVATE ${CMAKE_DL_LIBS})
  set_property(SOURCE "${df_root}/Filters/vtkOpenVDBLevelSetWriter.cxx" APPEND PROPERTY
    COMPILE_DEFINITIONS "DF_LEVELSET_MODULE=\"$<TARGET_FILE_NAME:vtkdf_LevelSet>\"")
  vtk_module_depend(DistanceFields::vtkDistanceFields vtkdf_LevelSet)
endif ()
