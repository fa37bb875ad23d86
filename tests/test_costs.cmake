# Read by CTest after the discovered tests (TEST_INCLUDE_FILES, tests/CMakeLists.txt). It gives the longest
# tests a COST: with -j, CTest starts tests in descending cost, and without timings of its own (a fresh clone,
# as in CI) every test costs the same and runs in the order it was added, which started the demo, the longest
# test, near the end with the other core idle. CTest replaces these figures with its own measurements once it
# has them (Testing/Temporary/CTestCostData.txt). Seconds on a 2-core machine with ../shared/data; only the
# order matters.
set(forensim_test_costs
    "Demo.WritesReportWithPicturesAndTimings" 260
    "SlowMummifyCli.RunsWritesOutputsAndResumes" 72
    "Sizes/PhantomModelSizes.CountsTrackingAndVolume/head_paper" 60
    "RealInputs.CtHeadWithTheSkullAsBone" 47
    "Sizes/PhantomModelSizes.CountsTrackingAndVolume/head_small" 44
    "Phantoms/ModelTets.VolumesTetsLabelsAndBoundaryMeetTheirTolerances/\"head\"" 35
    "TetIoLarge.RoundTripsOfAMillionTets" 26
    "Sizes/PhantomModelSizes.CountsTrackingAndVolume/arm_paper" 25)
# The tests that exist in this build (a subset where FORENSIM_TEST_MODULES lists some modules): the lists that
# gtest_discover_tests leaves in <target>_TESTS.
set(forensim_known_tests "")
get_cmake_property(forensim_variables VARIABLES)
foreach(variable IN LISTS forensim_variables)
  if(variable MATCHES "^forensim_.*_TESTS$")
    list(APPEND forensim_known_tests ${${variable}})
  endif()
endforeach()
# A listed name matches a test of that name, or one that adds a comment after it (value-parameterised tests:
# "Suite/Test.Case/param  # GetParam() = ...").
list(LENGTH forensim_test_costs forensim_cost_count)
math(EXPR forensim_last "${forensim_cost_count} - 2")
foreach(i RANGE 0 ${forensim_last} 2)
  math(EXPR j "${i} + 1")
  list(GET forensim_test_costs ${i} name)
  list(GET forensim_test_costs ${j} cost)
  foreach(test IN LISTS forensim_known_tests)
    string(FIND "${test} " "${name} " at)
    if(at EQUAL 0)
      set_tests_properties("${test}" PROPERTIES COST ${cost})
    endif()
  endforeach()
endforeach()
