# Warning and floating-point flags shared by every latsim target.
add_library(latsim_warnings INTERFACE)
add_library(latsim::warnings ALIAS latsim_warnings)
# Parameter declarations name only the fields they set (designated
# initializers); the others keep their defaults on purpose.
target_compile_options(latsim_warnings INTERFACE -Wall -Wextra -Werror -Wno-missing-field-initializers -ffp-contract=off)
if(LATSIM_SANITIZE)
  target_compile_options(latsim_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(latsim_warnings INTERFACE -fsanitize=address,undefined)
endif()

# latsim_add_library(NAME dir SOURCES ... DEPS ...): a module library latsim_<NAME>
# with the alias latsim::<NAME>, public headers in <dir>/include.
function(latsim_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(latsim_${name} STATIC ${ARG_SOURCES})
  add_library(latsim::${name} ALIAS latsim_${name})
  target_include_directories(latsim_${name} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/include")
  target_link_libraries(latsim_${name} PUBLIC latsim::warnings latsim::units ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(latsim_${name} PRIVATE ${LATSIM_FUZZ_COVERAGE})
  # The Python module (a shared object) links every library (cmake/LatsimPython.cmake).
  if(LATSIM_PYTHON)
    set_target_properties(latsim_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
endfunction()

# latsim_add_test(NAME SOURCES ... DEPS ... [LABELS ...]): a Catch2 test binary whose
# test cases are registered with ctest one by one.
function(latsim_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/tests")
  target_link_libraries(${name} PRIVATE latsim_catch_main latsim::warnings ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE LATSIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             LATSIM_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(NOT ARG_LABELS)
    set(ARG_LABELS fast)
  endif()
  catch_discover_tests(${name} TEST_PREFIX "${name}:" PROPERTIES LABELS "${ARG_LABELS}"
                       WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
endfunction()
