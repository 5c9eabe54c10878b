# A build against ParaView's own VTK (cmake -DParaView_DIR=...): the same modules as
# the system-VTK build, built into the ParaView plugin DistanceFields (ParaView/) in
# ParaView's layout, lib/<arch>/paraview-5.11/plugins/DistanceFields/. Programs, Python
# package and the test suite belong to the system-VTK build; this one has the plugin's
# tests (Testing/ParaView).
#
# Debian's paraview-dev declares CMake targets whose files come with python3-paraview
# (ParaView's Python modules, VTK::vtk*Python and ParaView::*Python, and pvpython); that
# package conflicts with python3-vtk9, which the system-VTK build needs, so the files are
# usually missing and ParaView's package fails on its check for them. The plugin links
# none of them: where a targets file references a missing file, declare its targets
# before the package does, which skips the check.
function(df_declare_targets_with_missing_files)
  get_filename_component(prefix "${ParaView_DIR}/../../../.." ABSOLUTE)
  foreach (targets IN ITEMS "vtk/VTKPython" "ParaViewPython" "ParaViewTools")
    file(GLOB configurations "${ParaView_DIR}/${targets}-targets-*.cmake")
    set(missing FALSE)
    foreach (configuration IN LISTS configurations)
      file(STRINGS "${configuration}" checks REGEX "_cmake_import_check_files_for_")
      foreach (check IN LISTS checks)
        if (check MATCHES "\"\\\${_IMPORT_PREFIX}([^\"]*)\"" AND NOT EXISTS "${prefix}${CMAKE_MATCH_1}")
          set(missing TRUE)
        endif ()
      endforeach ()
    endforeach ()
    if (NOT missing)
      continue ()
    endif ()
    file(STRINGS "${ParaView_DIR}/${targets}-targets.cmake" expected
      REGEX "^foreach\\(_cmake_expected_target IN ITEMS ")
    string(REGEX REPLACE "^foreach\\(_cmake_expected_target IN ITEMS (.*)\\)$" "\\1"
      expected "${expected}")
    separate_arguments(expected UNIX_COMMAND "${expected}")
    foreach (target IN LISTS expected)
      if (NOT TARGET "${target}")
        add_library("${target}" INTERFACE IMPORTED)
      endif ()
    endforeach ()
  endforeach ()
endfunction()
df_declare_targets_with_missing_files()

# Only the components this build needs: without COMPONENTS, ParaView's package also
# asks for its Qt client, whose help module Debian does not ship.
find_package(ParaView 5.11 REQUIRED COMPONENTS RemotingCore RemotingServerManager RemotingViews)
# ParaView's VTK, with the modules ours depend on (and their own dependencies: X11, GLEW).
find_package(VTK REQUIRED COMPONENTS CommonCore CommonDataModel CommonExecutionModel
  CommonSystem CommonMath vtksys ParallelCore FiltersGeneral IOCore RenderingCore RenderingVolume
  RenderingOpenGL2 glew)
# The wrapping hierarchy files of ParaView's modules (which the client-server wrapping of
# ours reads) come with python3-paraview too. Where that package is unpacked elsewhere
# (dpkg -x python3-paraview_*.deb ROOT, as Testing/ParaView/setup-paraview.sh does), point
# the modules to their files there.
set(DF_PARAVIEW_PYTHON_ROOT "/" CACHE PATH
  "Where python3-paraview's files are (dpkg -x root) when the package is not installed")
get_directory_property(imported_targets IMPORTED_TARGETS)
foreach (target IN LISTS imported_targets)
  get_target_property(hierarchy "${target}" INTERFACE_vtk_module_hierarchy)
  if (hierarchy AND NOT EXISTS "${hierarchy}")
    set(unpacked "${DF_PARAVIEW_PYTHON_ROOT}/${hierarchy}")
    if (NOT EXISTS "${unpacked}")
      message(FATAL_ERROR "${hierarchy} is missing: install python3-paraview, or unpack it "
        "(dpkg -x) and set DF_PARAVIEW_PYTHON_ROOT to where it is unpacked")
    endif ()
    set_target_properties("${target}" PROPERTIES INTERFACE_vtk_module_hierarchy "${unpacked}")
  endif ()
endforeach ()
find_package(PkgConfig REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)

# The plugin has no .vdb writer: OpenVDB links the system's TBB, which a ParaView binary
# of another build may load in another version beside its own.
set(DF_USE_OPENVDB OFF)
add_subdirectory(Filters/Core)
df_module_directory()
set(BUILD_SHARED_LIBS ON)
set(df_plugin_libdir "${CMAKE_INSTALL_LIBDIR}")
if (CMAKE_LIBRARY_ARCHITECTURE)
  set(df_plugin_libdir "lib/${CMAKE_LIBRARY_ARCHITECTURE}")
endif ()
paraview_plugin_scan(
  PLUGIN_FILES "${CMAKE_SOURCE_DIR}/ParaView/paraview.plugin"
  ENABLE_BY_DEFAULT ON
  PROVIDES_PLUGINS df_plugins)
paraview_plugin_build(
  PLUGINS ${df_plugins}
  # ParaView's layout on Debian: lib/<arch>/paraview-5.11/plugins/DistanceFields/.
  LIBRARY_DESTINATION "${df_plugin_libdir}"
  LIBRARY_SUBDIRECTORY "${PARAVIEW_PLUGIN_SUBDIR}"
  PLUGINS_COMPONENT paraview
  TARGET DistanceFieldsPlugins
  INSTALL_HEADERS OFF
  DISABLE_XML_DOCUMENTATION ON)

if (BUILD_TESTING)
  add_subdirectory(Testing/ParaView)
endif ()

# The plugin as a Debian package (cpack -G DEB in this build tree): vtkdistancefields-paraview,
# the plugin's folder only (the plugin and the two modules built against ParaView's VTK,
# found beside it through $ORIGIN), for Debian's ParaView under /usr whatever
# CMAKE_INSTALL_PREFIX is. It adds a folder under ParaView's plugins and changes no file
# of the paraview package (its paraview.plugins.xml included): load the plugin by path
# or through PV_PLUGIN_PATH.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME vtkdistancefields-paraview)
set(CPACK_PACKAGE_VENDOR "VTK Distance Fields")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "The VTK Distance Fields filters as a ParaView plugin (GPU and CPU distance fields of polygon meshes)")
set(CPACK_PACKAGE_CONTACT "VTK Distance Fields developers <vtkdf@vtk-distance-fields.invalid>")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL paraview)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_NAME vtkdistancefields-paraview)
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_SHLIBDEPS ON)
# The modules beside the plugin are its own, not another package's.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
  "${CMAKE_BINARY_DIR}/${df_plugin_libdir}/${PARAVIEW_PLUGIN_SUBDIR}/DistanceFields")
# dpkg-shlibdeps adds paraview (exactly the version built against: its VTK's ABI).
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_RECOMMENDS "libgl1-mesa-dri, libegl1, libegl-mesa0, libosmesa6")
include(CPack)
cpack_add_component(paraview DESCRIPTION "The ParaView plugin DistanceFields")
