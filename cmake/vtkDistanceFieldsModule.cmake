# The module's sources (included from the generated module directory, see CMakeLists.txt).
set(df_root "${CMAKE_SOURCE_DIR}")
set(classes
  "${df_root}/Filters/vtkDistanceFieldAlgorithm"
  "${df_root}/Filters/vtkLinearFactorDistanceField"
  "${df_root}/Filters/vtkPolyDataVoxelizer"
  "${df_root}/Filters/vtkChamferVoxelDistance"
  "${df_root}/Filters/vtkMedialAxisFilter"
  "${df_root}/Filters/vtkSegmentedDistanceField"
  "${df_root}/Filters/vtkDistanceFieldBlend"
  "${df_root}/Filters/vtkSegmentedDistanceContour"
  "${df_root}/Filters/vtkUnionClosestPoint"
  "${df_root}/Filters/vtkPenetrationDepth")
# The VTK-free cores (Filters/Core) are compiled once, as objects, into the module.
vtk_module_add_module(DistanceFields::vtkDistanceFields
  CLASSES ${classes}
  SOURCES "${df_root}/Filters/vtkDistanceFieldMesh.cxx" "${df_root}/Filters/vtkConvexPieces.cxx"
    $<TARGET_OBJECTS:vtkdf_core>
  PRIVATE_HEADERS "${df_root}/Filters/vtkDistanceFieldMesh.h" "${df_root}/Filters/vtkConvexPieces.h")
vtk_module_include(DistanceFields::vtkDistanceFields
  PUBLIC "$<BUILD_INTERFACE:${df_root}/Filters>"
  PRIVATE "$<TARGET_PROPERTY:vtkdf_core,INTERFACE_INCLUDE_DIRECTORIES>")
vtk_module_link(DistanceFields::vtkDistanceFields
  PRIVATE PkgConfig::EPOXY ${CMAKE_DL_LIBS} "${QHULL_R_LIBRARY}" "${MPFR_LIBRARY}" "${GMP_LIBRARY}")
