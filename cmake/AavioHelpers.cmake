# aavio_add_library(NAME SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
#   One static library per module folder, target aavio_<NAME>, alias aavio::<NAME>; installed
#   and exported as aavio::<NAME> (cmake/aavioConfig.cmake.in).
# aavio_add_test(NAME SOURCES ... DEPS ... [LABELS ...] [FIXTURES name])
#   One GoogleTest executable per module; every TEST becomes a CTest test.

function(aavio_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                         -Wcast-align -Wunused -Woverloaded-virtual -Wnull-dereference
                         -Wformat=2 -Wimplicit-fallthrough -Werror=return-type)
  # GCC's float-to-double check (clang's also flags every float in a double expression; the
  # GCC build is the warning gate).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wdouble-promotion)
  endif()
  # Config structs have in-class defaults and are filled with designated initializers
  # ({.width = 640}); the omitted fields keep their defaults on purpose.
  target_compile_options(${target} PRIVATE -Wno-missing-field-initializers)
  # No FMA contraction with any compiler, whatever the target: the same arithmetic, so the same
  # trajectories, whichever compiler built them (the x86-64 baseline and the AVX2 clones have no
  # FMA, so today's GCC builds are unchanged).
  target_compile_options(${target} PRIVATE -ffp-contract=off)
  # Lets GCC vectorise loops with a clamp (if-conversion of floating-point code); results are
  # unchanged (no -ffast-math).
  # -fno-math-errno: sqrt and friends need not set errno (nothing here reads it), so loops with
  # them vectorise; the values are the same (IEEE sqrt is correctly rounded either way).
  target_compile_options(${target} PRIVATE -fno-trapping-math -fno-math-errno)
  # GCC 12 warns falsely on `"literal" + std::string&&` at -O2 (GCC bug 105651).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(AAVIO_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(AAVIO_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                           -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  # Coverage instrumentation for the fuzz targets (they link libFuzzer itself).
  if(AAVIO_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

function(aavio_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(aavio_${name} STATIC ${ARG_SOURCES})
  add_library(aavio::${name} ALIAS aavio_${name})
  set_target_properties(aavio_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(aavio_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                                  $<INSTALL_INTERFACE:include>)
  target_compile_features(aavio_${name} PUBLIC cxx_std_20)
  target_link_libraries(aavio_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  aavio_set_warnings(aavio_${name})
  install(TARGETS aavio_${name} EXPORT aavioTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set_property(GLOBAL APPEND PROPERTY AAVIO_LIBRARIES aavio_${name})
endfunction()

function(aavio_add_test name)
  if(NOT AAVIO_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "FIXTURES" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  if(AAVIO_SANITIZE)
    target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/sanitizer_support.cpp)
    target_link_libraries(${name} PRIVATE ${CMAKE_DL_LIBS})
  endif()
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    AAVIO_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    AAVIO_TEST_TMP_DIR="${CMAKE_BINARY_DIR}/test_tmp")
  aavio_set_warnings(${name})
  set(properties LABELS "${ARG_LABELS}")
  if(ARG_FIXTURES)
    list(APPEND properties FIXTURES_REQUIRED ${ARG_FIXTURES})
  endif()
  gtest_discover_tests(${name} PROPERTIES ${properties} DISCOVERY_TIMEOUT 60)
endfunction()
