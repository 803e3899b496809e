# The include graph follows the layers of docs/architecture.md: a file includes only from its own
# layer or a lower one, and the core library neither CLI11 nor MathGL. Run by CTest:
#   cmake -DSOURCE_DIR=<repository> -P tests/check_layers.cmake
# Prints every offending include and fails if there is one.

# Layers from the bottom up; a file's layer is that of the first prefix of its path that matches.
set(layers brdf engine models io integrate fit tables scene plot bench cli python tests)
set(prefixes
  "include/brdfbake/brdf/=brdf" "kernels/=brdf"
  "include/brdfbake/error.h=engine" "include/brdfbake/engine.h=engine" "include/brdfbake/version.h=engine" "include/brdfbake/memory_limit.h=engine" "include/brdfbake/cancel.h=engine" "include/brdfbake/progress.h=engine"
  "host/engine/=engine"
  "include/brdfbake/output.h=io" "include/brdfbake/table.h=io" "host/io/=io"
  "include/brdfbake/spec.h=models" "include/brdfbake/fresnel_terms.h=models" "host/models/=models"
  "include/brdfbake/albedo.h=integrate" "include/brdfbake/analytic.h=integrate" "include/brdfbake/evaluate.h=integrate" "include/brdfbake/check.h=integrate" "include/brdfbake/fresnel_curve.h=integrate"
  "host/integrate/=integrate"
  "host/fit/=fit"
  "include/brdfbake/lut.h=tables" "include/brdfbake/table_kinds.h=tables" "include/brdfbake/api.h=tables" "host/tables/=tables"
  "host/scene/=scene"
  "host/plot/=plot"
  "benchmarks/=bench"
  "host/cli/=cli"
  "python/=python"
  "tests/=tests")
set(core_layers brdf engine models io integrate fit tables scene)

function(layer_of path out)
  foreach(entry IN LISTS prefixes)
    string(REPLACE "=" ";" kv "${entry}")
    list(GET kv 0 prefix)
    list(GET kv 1 layer)
    string(FIND "${path}" "${prefix}" at)
    if(at EQUAL 0)
      set(${out} ${layer} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

# Where an include "X" resolves: the include roots of the build, in order.
function(resolve include from out)
  get_filename_component(dir "${from}" DIRECTORY)
  foreach(root "${dir}" include host benchmarks tests)
    if(EXISTS "${SOURCE_DIR}/${root}/${include}")
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${SOURCE_DIR}/${root}/${include}")
      set(${out} "${rel}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  if(include STREQUAL "brdfbake/version.h")
    set(${out} "include/brdfbake/version.h" PARENT_SCOPE)
    return()
  endif()
  set(${out} "" PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}"
  "${SOURCE_DIR}/include/*.h" "${SOURCE_DIR}/kernels/*.cl" "${SOURCE_DIR}/host/*.h" "${SOURCE_DIR}/host/*.cpp"
  "${SOURCE_DIR}/benchmarks/*.h" "${SOURCE_DIR}/benchmarks/*.cpp" "${SOURCE_DIR}/python/*.cpp")
set(violations 0)
set(checked 0)
foreach(f IN LISTS files)
  layer_of("${f}" mine)
  if(mine STREQUAL "")
    if(f MATCHES "^(include|host)/")
      message("${f} belongs to no layer: add its prefix to the list at the top of this file")
      math(EXPR violations "${violations} + 1")
    endif()
    continue()
  endif()
  list(FIND layers ${mine} my_rank)
  list(FIND core_layers ${mine} in_core)
  file(STRINGS "${SOURCE_DIR}/${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]")
  foreach(line IN LISTS lines)
    math(EXPR checked "${checked} + 1")
    if(line MATCHES "#[ \t]*include[ \t]*<(CLI/|mgl2/)")
      if(in_core GREATER -1)
        message("${f}: the core (layer ${mine}) includes ${CMAKE_MATCH_1}: ${line}")
        math(EXPR violations "${violations} + 1")
      endif()
      continue()
    endif()
    if(NOT line MATCHES "#[ \t]*include[ \t]*\"([^\"]+)\"")
      continue()
    endif()
    resolve("${CMAKE_MATCH_1}" "${f}" target)
    if(target STREQUAL "")
      continue()  # generated files (baseline_flags.h) and the like
    endif()
    layer_of("${target}" theirs)
    if(theirs STREQUAL "")
      continue()
    endif()
    list(FIND layers ${theirs} their_rank)
    if(their_rank GREATER my_rank)
      message("${f} (layer ${mine}) includes ${target} (layer ${theirs}, higher)")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()
# Test names that CTest cannot run as given: catch_discover_tests splits a name at ';' (CTest
# then runs a filter that matches nothing and counts it a pass), and Catch reads a name that
# starts with '-' as an option (the test always fails).
file(GLOB test_sources "${SOURCE_DIR}/tests/*.cpp")
foreach(t IN LISTS test_sources)
  file(STRINGS "${t}" cases REGEX "TEST_CASE\\(\"")
  foreach(c IN LISTS cases)
    if(c MATCHES "TEST_CASE\\(\"-")
      message("${t}: a test name starts with '-', which Catch reads as an option: ${c}")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
  file(READ "${t}" text)
  string(REGEX MATCHALL "TEST_CASE\\(\"[^\"]*;[^\"]*\"" semi "${text}")
  if(semi)
    message("${t}: a test name holds a ';', which CTest's discovery splits")
    math(EXPR violations "${violations} + 1")
  endif()
endforeach()
list(LENGTH files n_files)
if(violations GREATER 0)
  message(FATAL_ERROR "${violations} violations: includes that go up a layer (of ${checked} in ${n_files} files) or test names CTest cannot run")
endif()
message("layers: ${checked} includes in ${n_files} files, none goes up a layer; every test name runs under CTest")
