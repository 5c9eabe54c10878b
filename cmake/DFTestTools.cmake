# Tests that need a tool this machine may lack (mpiexec, ParaView's pvserver and
# pvpython, a system-VTK build beside the ParaView one): where it is missing they are
# not added, and the configuration says so. Under CI (CI=true) a missing tool is an
# error instead: a CI machine that lost one must fail, not pass with fewer tests.
function(df_missing_test_tool tests reason)
  if ("$ENV{CI}" STREQUAL "true")
    message(FATAL_ERROR "${tests} needs ${reason}, which this machine lacks; under CI=true a "
      "missing test tool is an error, not a skip (install it: Testing/setup.sh, "
      "Testing/run-paraview-tests.sh).")
  endif ()
  message(STATUS "${tests} needs ${reason}: not added")
endfunction()
