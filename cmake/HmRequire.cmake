# SPDX-License-Identifier: GPL-2.0-or-later
#
# Every part of the build is required: a missing tool, library or target
# stops the configure step with a message naming what is missing and the
# command that installs it, instead of quietly building less (a smaller
# build would let `make test` pass with fewer tests).
#
# hm_require_targets(WHERE target...)
#     FATAL_ERROR unless every target exists (configured earlier).
# hm_require_path(WHAT PATH INSTALL)
#     FATAL_ERROR unless PATH exists; INSTALL is the command that provides it.
# hm_require_found(WHAT VAR INSTALL)
#     FATAL_ERROR unless ${VAR} is true (a find_* result).
function(hm_require_targets where)
    set(missing "")
    foreach(t ${ARGN})
        if(NOT TARGET ${t})
            list(APPEND missing ${t})
        endif()
    endforeach()
    if(missing)
        list(JOIN missing ", " m)
        message(FATAL_ERROR "${where}: required target(s) not defined: ${m}. "
            "They come from another folder of this tree; a folder is missing or was "
            "configured after this one (see the order in the top-level CMakeLists.txt).")
    endif()
endfunction()

function(hm_require_path what path install)
    if(NOT EXISTS "${path}")
        message(FATAL_ERROR "${what} is required but missing (${path}). Install it with: ${install}")
    endif()
endfunction()

function(hm_require_found what var install)
    if(NOT ${var})
        message(FATAL_ERROR "${what} is required but was not found (${var}). "
            "Install it with: ${install}")
    endif()
endfunction()
