# Installs the build into a scratch prefix, builds tests/install/consumer against it with find_package, runs it.
cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE result OUTPUT_QUIET)
if(result)
  message(FATAL_ERROR "cmake --install failed: ${result}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(result)
  message(FATAL_ERROR "configuring the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE result OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(result)
  message(FATAL_ERROR "building the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer OUTPUT_VARIABLE out RESULT_VARIABLE result)
# Round trip of (222.132, 37.5) mm and table 2.3's x3y5 −y deflection at 250 N (−1671 µm measured).
if(result OR NOT out MATCHES "x_mm=222\\.132 y_mm=37\\.500 dy_um=-16[5-8][0-9]\nsamples=[1-9][0-9]+")
  message(FATAL_ERROR "consumer printed '${out}' (exit ${result})")
endif()
message(STATUS "consumer: ${out}")
# The installed Python module, when it was built, imports from the prefix and finds the installed library.
file(GLOB python_module ${WORK_DIR}/prefix/lib/python3*/dist-packages/stiffpath*.so)
if(python_module)
  get_filename_component(python_dir ${python_module} DIRECTORY)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${python_dir}
                          /usr/bin/python3 -c "import stiffpath; print('%.9f' % stiffpath.Robot('oc-gu').ik([0.222132, 0.0375])[0])"
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE result)
  # θ1 of (222.132, 37.5) mm by eq. 2.2: atan2(37.5, 222.132) + acos(225.275 / 300) = 0.888588388 rad.
  if(result OR NOT out MATCHES "^0\\.88858838")
    message(FATAL_ERROR "the installed Python module printed '${out}' '${err}' (exit ${result})")
  endif()
  message(STATUS "installed Python module: theta1 = ${out}")
  # Its vision part, when built, sits beside it and finds the installed vision library (and OpenCV): a 10 mm line
  # drawn and measured, the length within 5 µm of the drawn one (docs/vision.md: a few µm).
  file(GLOB python_vision_module ${python_dir}/_stiffpath_vision*.so)
  if(python_vision_module)
    execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${python_dir} /usr/bin/python3 -c
                            "import stiffpath; v = stiffpath.vision; r = v.render_scan(length_m=0.01); print('%.2f' % ((v.scan(r.image, dpi=r.dpi).metrics.length_m - r.truth.length_m) * 1e6))"
                    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE result)
    if(result OR NOT out MATCHES "^-?[0-4]\\.[0-9][0-9]")
      message(FATAL_ERROR "the installed stiffpath.vision printed '${out}' '${err}' (exit ${result})")
    endif()
    message(STATUS "installed stiffpath.vision: length error ${out} µm")
  endif()
  # A staged install (DESTDIR, as packages are built) at the configured prefix puts the module in a folder that
  # Debian's Python searches, and it loads the library staged beside it (its RPATH is relative).
  execute_process(COMMAND ${CMAKE_COMMAND} -E env DESTDIR=${WORK_DIR}/stage ${CMAKE_COMMAND} --install ${BUILD_DIR}
                  RESULT_VARIABLE result OUTPUT_QUIET)
  file(GLOB_RECURSE staged_module ${WORK_DIR}/stage/*/stiffpath.cpython*.so)
  if(result OR NOT staged_module)
    message(FATAL_ERROR "DESTDIR=${WORK_DIR}/stage cmake --install staged no Python module (exit ${result})")
  endif()
  get_filename_component(staged_dir ${staged_module} DIRECTORY)
  string(REPLACE "${WORK_DIR}/stage" "" python_dir_on_target ${staged_dir})
  execute_process(COMMAND /usr/bin/python3 -c "import sys; print(chr(10).join(sys.path))" OUTPUT_VARIABLE search_path)
  string(REPLACE "\n" ";" search_path "${search_path}")
  if(NOT python_dir_on_target IN_LIST search_path)
    message(FATAL_ERROR "the module is installed in ${python_dir_on_target}, which /usr/bin/python3 does not search: ${search_path}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${staged_dir}
                          /usr/bin/python3 -c "import stiffpath; print(stiffpath.__file__)"
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE result)
  if(result OR NOT out MATCHES "^${staged_dir}")
    message(FATAL_ERROR "the staged Python module did not import from ${staged_dir}: '${out}' '${err}' (exit ${result})")
  endif()
  if(python_vision_module)
    execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${staged_dir}
                            /usr/bin/python3 -c "import stiffpath; print(stiffpath.vision.__file__)"
                    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE result)
    if(result OR NOT out MATCHES "^${staged_dir}/_stiffpath_vision")
      message(FATAL_ERROR "the staged stiffpath.vision did not import from ${staged_dir}: '${out}' '${err}' (exit ${result})")
    endif()
  endif()
  message(STATUS "staged Python module: ${python_dir_on_target}, searched by /usr/bin/python3")
endif()
# The installed CLI runs, and runs stiffpath-vision from libexec for the image commands.
execute_process(COMMAND ${WORK_DIR}/prefix/bin/stiffpath render-scan --help OUTPUT_VARIABLE out RESULT_VARIABLE result)
if(result OR NOT out MATCHES "render-scan")
  message(FATAL_ERROR "the installed stiffpath render-scan --help printed '${out}' (exit ${result})")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
