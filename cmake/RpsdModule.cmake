# rpsd_add_module(NAME [SOURCES ...] [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One static library per module folder: target rpsd_NAME, alias rpsd::NAME, built from every
# src/*.cpp (a new file needs no CMake edit) plus any generated SOURCES; public headers under
# NAME/include/rpsd/NAME/, installed and exported as rpsd::NAME.
set(RPSD_WARNING_FLAGS -Wall -Wextra -Wpedantic)

function(rpsd_warnings target)
  target_compile_options(${target} PRIVATE ${RPSD_WARNING_FLAGS}
    $<$<BOOL:${RPSD_WARNINGS_AS_ERRORS}>:-Werror>)
endfunction()

# RPSD_UNITY_BUILD (CI): the target's sources (a module library, the program, a test program)
# compiled as one translation unit, so their headers are parsed once, by the compiler and by
# clang-tidy.
function(rpsd_unity target)
  if(RPSD_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
  endif()
endfunction()

function(rpsd_add_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target rpsd_${name})
  file(GLOB module_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(${target} STATIC ${module_sources} ${M_SOURCES})
  add_library(rpsd::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name}
                                             POSITION_INDEPENDENT_CODE ON)
  rpsd_unity(${target})
  if(RPSD_UNITY_BUILD AND M_SOURCES)  # generated sources stay their own units
    set_source_files_properties(${M_SOURCES} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
  endif()
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  rpsd_warnings(${target})
  install(TARGETS ${target} EXPORT rpsdTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# rpsd_add_test(NAME SOURCES ... DEPS ...): one GoogleTest executable registered with CTest.
function(rpsd_add_test name)
  cmake_parse_arguments(T "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  rpsd_unity(${name})
  target_link_libraries(${name} PRIVATE ${T_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE RPSD_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  rpsd_warnings(${name})
  gtest_discover_tests(${name} WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}
                       PROPERTIES ENVIRONMENT "RPSD_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                       DISCOVERY_TIMEOUT 60)
endfunction()
