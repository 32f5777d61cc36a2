# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# ml_host_tests(TAG PREC SDK OTHER_PLUGIN_TARGET REJECT_REASON LABEL): the pymeshlab-like host
# tests of one FilterPlugin-API plugin binary (filter_implicit_fairing_ml<TAG>_<PREC>), used by
# tests/meshlab2025 (2025.07 float and double) and tests/meshlab2022 (2022.02 float).
# The host (pymeshlab_host.cpp) is linked to that SDK's libmeshlab-common.so; the test "reject"
# checks that OTHER_PLUGIN_TARGET's binary is refused with "... has different REJECT_REASON from
# the running MeshLab version." (no such test when OTHER_PLUGIN_TARGET is ""). Tests are named ml<TAG>_<PREC>_<case>, labelled LABEL.
set(ML_HOST_TESTS_DIR ${CMAKE_CURRENT_LIST_DIR})

function(ml_host_tests tag prec sdk other_plugin reject_reason label)
  set(host ml${tag}_host_${prec})
  add_executable(${host} ${ML_HOST_TESTS_DIR}/pymeshlab_host.cpp)
  set_target_properties(${host} PROPERTIES CXX_STANDARD 14 CXX_EXTENSIONS ON)
  target_compile_definitions(${host} PRIVATE ${MESHLAB_${tag}_DEFINES_${prec}})
  target_include_directories(${host} SYSTEM PRIVATE ${MESHLAB_${tag}_INCLUDE_DIRS})
  target_link_libraries(${host} PRIVATE meshlab${tag}::common_${prec}
    Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml)
  # the plugins are loaded at run time: build them with the host
  add_dependencies(${host} filter_implicit_fairing_ml${tag}_${prec} ${other_plugin})
  set(other "")
  if(other_plugin)
    set(other $<TARGET_FILE:${other_plugin}>)
  endif()

  # engine_reference (tests/meshlab2020) with this SDK's vcglib and this precision's CMeshO
  set(ref ml${tag}_engine_reference_${prec})
  add_executable(${ref} ${ML_HOST_TESTS_DIR}/../meshlab2020/engine_reference.cpp
    ${sdk}/src/src/vcglib/wrap/ply/plylib.cpp)
  target_include_directories(${ref} SYSTEM PRIVATE ${sdk}/src/src/vcglib)
  target_link_libraries(${ref} PRIVATE fairing::vcg_adapters fairing::parameters
    fairing::fairing)
  set_target_properties(${ref} PROPERTIES CXX_STANDARD 14 CXX_EXTENSIONS ON)
  if(prec STREQUAL double)
    target_compile_definitions(${ref} PRIVATE ENGINE_REFERENCE_DOUBLE)
  endif()

  set(env PREC=${prec}
    HOST=$<TARGET_FILE:${host}>
    ENGINE_REFERENCE=$<TARGET_FILE:${ref}>
    PLUGIN=$<TARGET_FILE:filter_implicit_fairing_ml${tag}_${prec}>
    OTHER_PLUGIN=${other}
    "REJECT_REASON=${reject_reason}"
    PLUGINS_DIR=${sdk}/${prec}/distrib/plugins)
  set(tests "")
  # t(NAME ARGS...): one test with its own work dir
  macro(t name)
    add_test(NAME ml${tag}_${prec}_${name}
      COMMAND ${CMAKE_COMMAND} -E env ${env}
              WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/work/${prec}/${name}
              bash ${ML_HOST_TESTS_DIR}/run_test.sh ${ARGN})
    list(APPEND tests ml${tag}_${prec}_${name})
  endmacro()

  t(list list)
  if(other_plugin)
    t(reject_other_binary reject)
  endif()
  t(failure_nonmanifold failure)
  t(warnings_explicit_unstable warnings)
  foreach(f umbrella scale_dependent curvature_flow)
    foreach(mesh sphere grid)                     # defaults on a closed and an open mesh
      t(${f}_${mesh} run ${f} ${mesh})
    endforeach()
    foreach(check quality-fixed selection)        # constrained vertices stay bit-identical
      string(REPLACE "-" "_" n ${check})
      t(${f}_${n} ${check} ${f})
    endforeach()
  endforeach()
  # keyword arguments of every parameter: floats, ints, bools, enums by label and by index
  t(umbrella_first_order_3steps run umbrella twocomp
    timestep=0.5 stepsmoothnum=3 "order=L (first order)" freezeoperator=True tolerance=1e-8
    maxiterations=500)
  t(umbrella_explicit run umbrella sphere
    integration=Explicit order=0 timestep=0.2 stepsmoothnum=4 preservevolume=False)
  t(scale_dependent_smooth_boundary run scale_dependent grid
    "boundarymode=Smooth boundary curve" openinvariant=1 stepsmoothnum=2)
  t(curvature_flow_virtual_vertex run curvature_flow grid
    boundarymode=2 timestep=0.5 acceptunconverged=True "order=L2 (second order)")
  t(curvature_flow_quality_ramp_inverted run curvature_flow twocomp+ramp
    qualityweights=True invertquality=True)
  set_tests_properties(${tests} PROPERTIES LABELS ${label} TIMEOUT 300)
endfunction()
