# hapcine_library(NAME folder DEPS ...)
#   One static library per folder from every *.cc that is not a test, and one
#   test executable (hapcine_<folder>_tests) from the folder's *_test.cc files,
#   each test file beside the code it tests.
function(hapcine_library name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB _all CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  set(_srcs "")
  set(_tests "")
  foreach(f ${_all})
    if(f MATCHES "_test\\.cc$")
      list(APPEND _tests ${f})
    else()
      list(APPEND _srcs ${f})
    endif()
  endforeach()
  if(NOT _srcs)
    message(FATAL_ERROR "hapcine_library(${name}): no sources in ${CMAKE_CURRENT_SOURCE_DIR}")
  endif()
  add_library(hapcine_${name} STATIC ${_srcs})
  target_include_directories(hapcine_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(hapcine_${name} PUBLIC ${ARG_DEPS})
  if(HAPCINE_BUILD_TESTS AND _tests)
    add_executable(hapcine_${name}_tests ${_tests})
    target_link_libraries(hapcine_${name}_tests PRIVATE hapcine_${name} ${ARG_TEST_DEPS}
                          GTest::gtest GTest::gtest_main GTest::gmock)
    target_compile_definitions(hapcine_${name}_tests PRIVATE
        HAPCINE_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
        HAPCINE_BINARY_DIR="${PROJECT_BINARY_DIR}")
    gtest_discover_tests(hapcine_${name}_tests DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
  endif()
endfunction()
