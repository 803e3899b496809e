# The install_consumer test: installs the build tree BUILD_DIR into WORK_DIR/prefix, then builds
# and runs the project CONSUMER_DIR against it twice: with find_package(brdfbake) (CMake) and
# with the flags of `pkg-config --cflags --libs brdfbake` (one compiler call). Fails on any step.
# Run as: cmake -DBUILD_DIR=... -DCONSUMER_DIR=... -DWORK_DIR=... -DCXX=... [-DCONFIG=...] -P consumer_test.cmake
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "install_consumer: ${what}: ok ${out}")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
set(config_arg "")
if(CONFIG)
  set(config_arg --config ${CONFIG})
endif()
step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} ${config_arg})
foreach(f lib/cmake/brdfbake/brdfbakeConfig.cmake lib/cmake/brdfbake/brdfbakeConfigVersion.cmake
          lib/pkgconfig/brdfbake.pc include/brdfbake/version.h include/brdfbake/brdf/models.h bin/brdfbake)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install_consumer: ${f} is not installed")
  endif()
endforeach()

# CMake: find_package(brdfbake) and brdfbake::core.
step("configure the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/cmake-build
     -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release)
step("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-build)
step("run the consumer (find_package)" ${WORK_DIR}/cmake-build/consumer)

# pkg-config: the same source, compiled and linked with the flags brdfbake.pc gives.
find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
step("pkg-config --cflags --libs brdfbake" ${PKG_CONFIG} --cflags --libs brdfbake)
string(STRIP "${step_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
step("compile and link with pkg-config's flags"
     ${CXX} -std=c++17 -O2 ${CONSUMER_DIR}/consumer.cpp ${flags} -o ${WORK_DIR}/consumer-pkg-config)
step("run the consumer (pkg-config)" ${WORK_DIR}/consumer-pkg-config)
