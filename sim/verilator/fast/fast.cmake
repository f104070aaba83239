# SPDX-License-Identifier: GPL-2.0-or-later
#
# sim/verilator/fast: the fast board model (fast_model.h) and its
# differential test against the Verilated firmwares (vboard-fastdiff).
# Included by sim/verilator/CMakeLists.txt after the firmware loop, which
# collects VB_FAST_IDROM_ARGS (board firmware .idrom.hex, per local-bus firmware).

set(VB_FAST_DIR ${CMAKE_CURRENT_SOURCE_DIR}/fast)
set(VB_FAST_IDROMS ${VB_OUT}/fast_idroms.cpp)
set(vb_fast_hex "")
foreach(a ${VB_FAST_IDROM_ARGS})
    if(a MATCHES "\\.hex$")
        list(APPEND vb_fast_hex ${a})
    endif()
endforeach()
add_custom_command(
    OUTPUT ${VB_FAST_IDROMS}
    COMMAND ${Python3_EXECUTABLE} ${VB_FAST_DIR}/fast_idroms.py ${VB_FAST_IDROMS}
            ${VB_FAST_IDROM_ARGS}
    DEPENDS ${vb_fast_hex} ${VB_FAST_DIR}/fast_idroms.py
    COMMENT "fast model: IDROM table"
    VERBATIM)
add_custom_target(vb_fast_idroms DEPENDS ${VB_FAST_IDROMS})
add_dependencies(vb_fast_idroms hm2gen_outputs)

# The models: our own code, warnings as errors, sanitizers with SANITIZE=ON
# (unlike the Verilated code, they are cheap enough to check).
add_library(vb_fast STATIC
    ${VB_FAST_DIR}/fast_config.cpp ${VB_FAST_DIR}/fast_basic.cpp
    ${VB_FAST_DIR}/fast_encoder.cpp ${VB_FAST_DIR}/fast_stepgen.cpp
    ${VB_FAST_DIR}/fast_pwm.cpp ${VB_FAST_DIR}/fast_model.cpp ${VB_FAST_IDROMS})
add_dependencies(vb_fast vb_fast_idroms vboard_firmware)
target_include_directories(vb_fast PUBLIC ${VB_FAST_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/src
    ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_compile_options(vb_fast PRIVATE ${VB_OWN_FLAGS} -O2)
set_property(TARGET vb_fast PROPERTY POSITION_INDEPENDENT_CODE ON)

# vboard-fastdiff: both models side by side (make test runs short runs per
# module through tests/vboard/test_fast_models.py, make bench long ones).
add_executable(vboard-fastdiff ${VB_FAST_DIR}/fast_diff.cpp src/pins.cpp src/vcd2fst.cpp)
target_include_directories(vboard-fastdiff PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src
    ${CMAKE_CURRENT_SOURCE_DIR}/include ${VB_OUT}/fwinfo)
target_compile_options(vboard-fastdiff PRIVATE ${VB_OWN_FLAGS} -O2)
target_link_libraries(vboard-fastdiff PRIVATE vb_fast vb_lb_models vb_verilated vb_fstcpp
    ${VB_LZ4_LIB} ZLIB::ZLIB)
foreach(top ${VB_LB_MODELS})
    target_link_libraries(vboard-fastdiff PRIVATE V${top})
endforeach()

# Unit tests of the IDROM reader and the DDS closed forms: ctest.
add_executable(vboard_fast_unit_tests ${VB_FAST_DIR}/fast_unit_tests.cpp src/pins.cpp)
target_compile_options(vboard_fast_unit_tests PRIVATE ${VB_OWN_FLAGS})
target_link_libraries(vboard_fast_unit_tests PRIVATE vb_fast)
set_target_properties(vboard_fast_unit_tests PROPERTIES
    RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
add_test(NAME vboard_fast_unit_tests COMMAND vboard_fast_unit_tests)
