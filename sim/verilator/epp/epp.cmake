# SPDX-License-Identifier: GPL-2.0-or-later
#
# EPP boards of the virtual board (included by sim/verilator/CMakeLists.txt):
# the Pluto-P with the Verilated pluto_servo and pluto_step firmwares
# (pluto_board.cpp) and their firmware files $HM_FIRMWARE_DIR/<fw>.rbf, and
# the 7i43 and the 7i90 with the Verilated hm2 EPP firmwares (hm2_epp_board.cpp; their
# .BIT files and fwinfo headers come from the main CMakeLists).  Both are
# EppFpgaBoards (epp_fpga_board.cpp: a Verilated firmware behind the port of
# epp_port_board.cpp).
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
# The 7i43 firmwares, for both sizes: hm2/7i43/ (400K) and hm2/7i43-2/ (the
# 200K part, 3s200tq144; descriptions based on the 7i43's, their IDROM says
# FPGASize 200; images for `vboard --board 7i43-2`).  The main CMakeLists
# writes both directories' .BIT files and fwinfo headers.
set(VB_7I43_SIZED_BITS "")
foreach(fw svst4_4 sv8 svst2_4_7i47)
    string(TOUPPER ${fw} FW)
    foreach(board 7i43 7i43-2)
        string(MAKE_C_IDENTIFIER "hm2_${board}_${fw}" top)
        set(gen ${VB_GENERATED}/${board}/${FW})
        vboard_verilate(NAME V${top} TOP ${top}
            SOURCES ${gen}/${top}.v
            INCLUDE_DIRS ${gen}
            LIBRARY_DIRS ${VB_HDL}/hostmot2 ${VB_HDL}/common
            DEPENDS ${gen}/${top}_inc.v ${VB_HDL_SOURCES})
        list(APPEND VBOARD_LIBS V${top})
    endforeach()
    # Mesa's firmware packages also have hm2/7i43-4/ for the 400K part (the
    # same file as hm2/7i43/).  LinuxCNC's sample configurations name it.
    set(gen ${VB_GENERATED}/7i43/${FW})
    set(bit4 ${HM_FIRMWARE_DIR}/hm2/7i43-4/${FW}.BIT)
    add_custom_command(
        OUTPUT ${bit4}
        COMMAND ${Python3_EXECUTABLE} ${VBFW} ${gen}/${FW}.json --bit ${bit4}
        DEPENDS ${gen}/${FW}.json ${gen}/${FW}.idrom.hex ${VBFW}
        COMMENT "vbfw 7i43-4/${FW}.BIT"
        VERBATIM)
    list(APPEND VB_7I43_SIZED_BITS ${bit4})
endforeach()
# The 7i90's firmware (it boots it from its flash: vboard --board 7i90).
foreach(fw SVST8_4)
    string(MAKE_C_IDENTIFIER "hm2_7i90_${fw}" top)
    string(TOLOWER ${top} top)
    set(gen ${VB_GENERATED}/7i90/${fw})
    vboard_verilate(NAME V${top} TOP ${top}
        SOURCES ${gen}/${top}.v
        INCLUDE_DIRS ${gen}
        LIBRARY_DIRS ${VB_HDL}/hostmot2 ${VB_HDL}/common
        DEPENDS ${gen}/${top}_inc.v ${VB_HDL_SOURCES})
    list(APPEND VBOARD_LIBS V${top})
endforeach()
add_custom_target(vboard_7i43_sized_firmware ALL DEPENDS ${VB_7I43_SIZED_BITS})
add_dependencies(vboard_7i43_sized_firmware hm2gen_outputs)
list(APPEND VBOARD_SOURCES ${VB_EPP_DIR}/epp_port_board.cpp ${VB_EPP_DIR}/epp_fpga_board.cpp
                           ${VB_EPP_DIR}/pluto_board.cpp ${VB_EPP_DIR}/hm2_epp_board.cpp)
list(APPEND VBOARD_FACTORIES vb_factory_pluto vb_factory_hm2_epp)
