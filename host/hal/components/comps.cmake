# SPDX-License-Identifier: GPL-2.0-or-later
#
# Every *.comp in this folder -> halcompile --preprocess -> NAME.c -> lib/rtlib/NAME.so
# (or bin/NAME for `option userspace`).  Adding a .comp file is all it takes:
# the glob re-runs when files appear or disappear.  Whether a component is
# realtime or userspace is asked at configure time (one halcompile --kind run
# for all files); if a file's kind changes later, its preprocess step notices,
# touches comp-kinds.stamp (which makes the next build re-configure) and fails
# with a message saying to build again.
find_package(Python3 3.11 REQUIRED COMPONENTS Interpreter)
set(HALCOMPILE_PKG ${CMAKE_SOURCE_DIR}/tools/halcompile)
file(GLOB HALCOMPILE_PY CONFIGURE_DEPENDS ${HALCOMPILE_PKG}/halcompile/*.py)
file(GLOB HM_COMP_FILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.comp)
set(HM_COMP_OUT ${CMAKE_CURRENT_BINARY_DIR}/generated)
set(HM_COMP_STAMP ${CMAKE_CURRENT_BINARY_DIR}/comp-kinds.stamp)
file(MAKE_DIRECTORY ${HM_COMP_OUT})
if(NOT EXISTS ${HM_COMP_STAMP})
    file(WRITE ${HM_COMP_STAMP} "")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${HM_COMP_STAMP})
set(HALCOMPILE_CMD ${CMAKE_COMMAND} -E env PYTHONPATH=${HALCOMPILE_PKG}
    ${Python3_EXECUTABLE} -m halcompile)

# conv_IN_OUT: one component per type pair of LinuxCNC 2.9, and the pairs
# with s64/u64 it lacks, from conv.comp.in.  *_RANGE: the pairs whose input
# can leave the output's range (out-of-range pin, clamp parameter).
set(HM_CONV_PAIRS bit:float bit:s32 bit:u32 float:s32 float:u32 s32:bit s32:float s32:u32
    u32:bit u32:float u32:s32
    bit:s64 bit:u64 float:s64 float:u64 s32:s64 s32:u64 u32:s64 u32:u64 s64:bit s64:float
    s64:s32 s64:u32 s64:u64 u64:bit u64:float u64:s32 u64:u32 u64:s64)
set(HM_CONV_RANGE float:s32 float:u32 s32:bit s32:u32 u32:bit u32:s32
    float:s64 float:u64 s32:u64 s64:bit s64:s32 s64:u32 s64:u64 u64:bit u64:s32 u64:u32 u64:s64)
set(HM_CONV_DIR ${CMAKE_CURRENT_BINARY_DIR}/conv)
foreach(pair ${HM_CONV_PAIRS})
    string(REPLACE ":" ";" io ${pair})
    list(GET io 0 IN)
    list(GET io 1 OUT)
    string(TOUPPER "K_${IN}" K_IN)
    string(TOUPPER "K_${OUT}" K_OUT)
    set(FP nofp)
    if(IN STREQUAL "float" OR OUT STREQUAL "float")
        set(FP fp)
    endif()
    set(RANGE_DECLS "")
    if(pair IN_LIST HM_CONV_RANGE)
        set(RANGE_DECLS "pin out bit out_of_range \"TRUE when in did not fit in out\";\nparam rw bit clamp \"TRUE: out is limited to the range of its type\";")
    endif()
    configure_file(${CMAKE_CURRENT_SOURCE_DIR}/conv.comp.in ${HM_CONV_DIR}/conv_${IN}_${OUT}.comp
                   @ONLY)
    list(APPEND HM_COMP_FILES ${HM_CONV_DIR}/conv_${IN}_${OUT}.comp)
endforeach()

set(comp_kinds "")
if(HM_COMP_FILES)
    execute_process(COMMAND ${HALCOMPILE_CMD} --kind ${HM_COMP_FILES}
                    OUTPUT_VARIABLE comp_kinds RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "halcompile --kind failed on the .comp files (${rc})")
    endif()
    string(REPLACE "\n" ";" comp_kinds "${comp_kinds}")
endif()

set(i 0)
foreach(comp ${HM_COMP_FILES})
    list(GET comp_kinds ${i} line)
    math(EXPR i "${i} + 1")
    string(REPLACE " " ";" line "${line}")
    list(GET line 0 name)
    list(GET line 1 kind)
    set(csrc ${HM_COMP_OUT}/${name}.c)
    add_custom_command(
        OUTPUT ${csrc}
        COMMAND ${HALCOMPILE_CMD} --preprocess --expect-kind ${kind} --kind-stamp ${HM_COMP_STAMP}
                -o ${csrc} ${comp}
        DEPENDS ${comp} ${HALCOMPILE_PY}
        COMMENT "halcompile ${name}.comp"
        VERBATIM)
    # Target comp_NAME, file NAME: component names may equal other targets.
    if(kind STREQUAL "user")
        add_executable(comp_${name} ${csrc})
        set_target_properties(comp_${name} PROPERTIES OUTPUT_NAME ${name})
    else()
        add_library(comp_${name} MODULE ${csrc})
        set_target_properties(comp_${name} PROPERTIES
            OUTPUT_NAME ${name}
            PREFIX ""
            LIBRARY_OUTPUT_DIRECTORY ${HM_RTLIB_DIR}
            C_VISIBILITY_PRESET hidden)
        target_link_options(comp_${name} PRIVATE -Wl,-Bsymbolic)
    endif()
    target_link_libraries(comp_${name} PRIVATE halcomp hal m)
    # headers next to the .comp files (`include "math/pid_math.h";`)
    target_include_directories(comp_${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
endforeach()
