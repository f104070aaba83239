# SPDX-License-Identifier: GPL-2.0-or-later
#
# hal_add_rt_module(NAME src...)   a realtime component: lib/rtlib/NAME.so,
#                                  loaded by rtapi_app on `loadrt NAME`.
# hal_add_user_program(NAME src...) a userspace program in bin/ using libhal.
#
# Realtime modules are built with hidden visibility and -Bsymbolic so two
# modules' private symbols never interpose each other when rtapi_app loads
# them with RTLD_GLOBAL; what a module offers other modules is marked
# RTAPI_EXPORT (see rtapi.h).  Symbols of modules loaded earlier (hostmot2
# for hm2_pci) resolve at load time, so undefined symbols are allowed.
#
# The libhal target is called `hal` and is defined in host/hal/lib.
function(hal_add_rt_module name)
    add_library(${name} MODULE ${ARGN})
    set_target_properties(${name} PROPERTIES
        PREFIX ""
        LIBRARY_OUTPUT_DIRECTORY ${HM_RTLIB_DIR}
        C_VISIBILITY_PRESET hidden
        CXX_VISIBILITY_PRESET hidden)
    target_link_libraries(${name} PRIVATE hal)
    target_link_options(${name} PRIVATE -Wl,-Bsymbolic)
endfunction()

function(hal_add_user_program name)
    add_executable(${name} ${ARGN})
    target_link_libraries(${name} PRIVATE hal)
endfunction()
