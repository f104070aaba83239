# SPDX-License-Identifier: GPL-2.0-or-later
#
# EPP boards of the virtual board (included by sim/verilator/CMakeLists.txt):
# the Pluto-P with the Verilated pluto_servo and pluto_step firmwares
# (pluto_board.cpp) and their firmware files $HM_FIRMWARE_DIR/<fw>.rbf.
set(VB_EPP_DIR ${CMAKE_CURRENT_SOURCE_DIR}/epp)
file(GLOB VB_PLUTO_HDL CONFIGURE_DEPENDS ${VB_HDL}/pluto/*.v ${VB_HDL}/common/*.v)
set(VB_PLUTO_RBF "")
foreach(fw pluto_servo pluto_step)
    vboard_verilate(NAME V${fw} TOP ${fw}
        SOURCES ${VB_HDL}/pluto/${fw}.v
        LIBRARY_DIRS ${VB_HDL}/pluto ${VB_HDL}/common
        DEPENDS ${VB_PLUTO_HDL})
    list(APPEND VBOARD_LIBS V${fw})
    set(rbf ${HM_FIRMWARE_DIR}/${fw}.rbf)
    add_custom_command(
        OUTPUT ${rbf}
        COMMAND ${Python3_EXECUTABLE} ${VB_EPP_DIR}/make_rbf.py ${fw} ${rbf}
        DEPENDS ${VB_EPP_DIR}/make_rbf.py ${VBFW}
        COMMENT "vbfw ${fw}.rbf"
        VERBATIM)
    list(APPEND VB_PLUTO_RBF ${rbf})
endforeach()
add_custom_target(vboard_pluto_firmware ALL DEPENDS ${VB_PLUTO_RBF})
list(APPEND VBOARD_SOURCES ${VB_EPP_DIR}/pluto_board.cpp)
list(APPEND VBOARD_FACTORIES vb_factory_pluto)
