# SPDX-License-Identifier: GPL-2.0-or-later
#
# The virtual local-bus board as a library (included at the end of
# sim/verilator/CMakeLists.txt): lib/libvboard_inproc.so, the same
# LocalBusBoard and Verilated firmwares as bin/vboard behind the C table of
# vboard/inproc.h.  hm2_sim inproc=1 dlopen()s it (docs/hm2_sim.md).  Only
# vbi_get_api is exported (inproc.map); the Verilator runtime and the
# models stay private to the library.
set(VB_INPROC_DIR ${CMAKE_CURRENT_SOURCE_DIR}/inproc)
# The models and the Verilator runtime go into a shared library too.
set_property(TARGET vb_verilated vb_lb_models vb_fstcpp PROPERTY POSITION_INDEPENDENT_CODE ON)
foreach(top ${VB_LB_MODELS})
    get_target_property(vb_kind V${top} TYPE)
    if(NOT vb_kind STREQUAL "INTERFACE_LIBRARY")
        set_property(TARGET V${top} PROPERTY POSITION_INDEPENDENT_CODE ON)
    endif()
endforeach()
add_library(vboard_inproc SHARED ${VB_INPROC_DIR}/vbi.cpp
    src/localbus.cpp src/pins.cpp src/fwimage.cpp src/spiflash.cpp src/flashport.cpp src/jtagtap.cpp
    src/vcd2fst.cpp)
target_include_directories(vboard_inproc PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src
    ${CMAKE_CURRENT_SOURCE_DIR}/include ${VB_OUT}/fwinfo)
target_compile_options(vboard_inproc PRIVATE ${VB_OWN_FLAGS})
target_compile_definitions(vboard_inproc PRIVATE VBOARD_HAVE_FST=1)
target_link_libraries(vboard_inproc PRIVATE vb_lb_models vb_verilated vb_fstcpp vb_fast
    ${VB_LZ4_LIB} ZLIB::ZLIB -Wl,--version-script=${VB_INPROC_DIR}/inproc.map)
foreach(top ${VB_LB_MODELS})
    target_link_libraries(vboard_inproc PRIVATE V${top})
endforeach()
set_target_properties(vboard_inproc PROPERTIES LINK_DEPENDS ${VB_INPROC_DIR}/inproc.map
    CXX_VISIBILITY_PRESET hidden)
add_dependencies(vboard_inproc vboard_firmware)
# hm2_sim inproc=1 loads it: built with the module.
add_dependencies(hm2_sim vboard_inproc)
