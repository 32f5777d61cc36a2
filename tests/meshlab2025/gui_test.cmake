# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# ml_gui_test(TAG GUI PLUGIN_TARGET LABEL): the GUI test (gui_test.sh) of the float plugin
# PLUGIN_TARGET in the MeshLab application GUI (2025.07 or 2022.02, built into the SDK cache by
# scripts/meshlab-<TAG>-sdk.sh) under Xvfb, started through scripts/meshlab2025.sh. Test
# ml<TAG>_gui, labelled LABEL; screenshots in <build>/tests/meshlab<TAG>/work/gui/.
set(ML_GUI_TEST_DIR ${CMAKE_CURRENT_LIST_DIR})

function(ml_gui_test tag gui plugin label)
  set(work ${CMAKE_CURRENT_BINARY_DIR}/work/gui)
  add_test(NAME ml${tag}_gui
    COMMAND ${CMAKE_COMMAND} -E env
            REPO=${PROJECT_SOURCE_DIR} BUILD_DIR=${CMAKE_BINARY_DIR} WORK_DIR=${work}
            FAIRING_GUI_HOME=${work}/home MESHLAB_GUI=${gui} FAIRING_MESHLAB=${tag}
            FAIRING_PLUGIN=$<TARGET_FILE:${plugin}>
            bash ${ML_GUI_TEST_DIR}/gui_test.sh)
  # xvfb-run -a races when several start at once: one Xvfb test at a time (as tests/meshlab2020)
  set_tests_properties(ml${tag}_gui PROPERTIES LABELS ${label} RESOURCE_LOCK xvfb TIMEOUT 900)
endfunction()
