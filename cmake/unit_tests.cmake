# Unit tests live beside the module they test (<module>/test/), each module's CMake adding its own
# binary with ipe_unit_tests(); every TEST is its own CTest case, label `unit`. The fakes of a module's
# interfaces sit in its test folder as an INTERFACE library (ipe_<module>_fakes) that the tests of
# other modules and the fuzz targets link: one copy of each fake.
find_package(GTest REQUIRED)
include(GoogleTest)

# ipe_unit_tests(NAME LIBRARIES lib...): the test binary NAME from every .cc of the calling folder.
function(ipe_unit_tests name)
  cmake_parse_arguments(arg "" "" "LIBRARIES" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  add_executable(${name} ${sources})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES} GTest::gtest_main GTest::gmock)
  ipe_host_target(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 30 PROPERTIES LABELS unit)
  set_property(GLOBAL APPEND PROPERTY IPE_UNIT_TEST_BINARIES ${name})
endfunction()

# ipe_test_fakes(NAME LIBRARIES lib...): the calling test folder's headers (fakes, fixtures) as the
# INTERFACE library NAME.
function(ipe_test_fakes name)
  cmake_parse_arguments(arg "" "" "LIBRARIES" ${ARGN})
  add_library(${name} INTERFACE)
  target_include_directories(${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${name} INTERFACE ${arg_LIBRARIES})
endfunction()

# After every module: `ipe_unit_tests` builds all unit test binaries (tools/test builds it under ASan).
function(ipe_unit_tests_target)
  get_property(binaries GLOBAL PROPERTY IPE_UNIT_TEST_BINARIES)
  add_custom_target(ipe_unit_tests DEPENDS ${binaries})
endfunction()
