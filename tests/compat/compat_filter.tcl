# SPDX-License-Identifier: GPL-2.0-or-later
#
# compat_filter.tcl - the compat rule (docs/compat.md) for the HAL commands
# a Tcl HAL file runs.  make compat loads this into haltcl before the file
# (as a string, so its procedures carry no file location of their own):
# every HAL command - `hal CMD ...` and the commands setp, net, loadrt,
# ... - is sent to make compat (tests/compat/tclfilter.py) over a local
# TCP connection first, which answers, judged by the same rule as the
# lines of .hal files:
#   keep                  the command runs as written
#   remove PART WHY       the command does not run (its result is empty)
#   rewrite PART WHY W... the words W... run instead
# Before the answer, make compat may send `first W...` lines: HAL commands
# to run first (the motion stand-in at motmod's line); an error in one is
# the command's error.
# Words travel hex-encoded (UTF-8), separated by blanks, one request a line.

namespace eval ::compat {
    variable sock ""
    namespace eval real {}

    proc hex {s} {
        return [binary encode hex [encoding convertto utf-8 $s]]
    }

    proc unhex {h} {
        return [encoding convertfrom utf-8 [binary decode hex $h]]
    }

    proc connect {port} {
        variable sock
        set sock [socket 127.0.0.1 $port]
        fconfigure $sock -translation lf -encoding ascii -buffering line
    }

    # The answer for one command (a list of words), as a list:
    # keep | remove | rewrite WORD...
    proc ask {words} {
        variable sock
        set req {}
        foreach w $words {
            lappend req [hex $w]
        }
        puts $sock [join $req " "]
        while 1 {
            if {[gets $sock reply] < 0} {
                error "compat: make compat did not answer for: $words"
            }
            set parts [split $reply " "]
            set kind [lindex $parts 0]
            if {$kind ne "first"} {
                break
            }
            set cmd {}
            foreach h [lrange $parts 1 end] {
                lappend cmd [unhex $h]
            }
            ::compat::real::hal {*}$cmd
        }
        if {$kind ne "rewrite"} {
            return $kind
        }
        set out [list rewrite]
        foreach h [lrange $parts 1 end] {
            lappend out [unhex $h]
        }
        return $out
    }

    # The HAL command NAME with the arguments ARGL, run (when kept) in the
    # frame of the code that called it.
    proc filtered {name argl} {
        set answer [ask [linsert $argl 0 $name]]
        switch -- [lindex $answer 0] {
            keep {
                return [uplevel 2 [linsert $argl 0 ::compat::real::$name]]
            }
            remove {
                return ""
            }
            rewrite {
                return [uplevel 2 [linsert [lrange $answer 1 end] 0 ::compat::real::hal]]
            }
        }
        error "compat: unexpected answer '$answer'"
    }

    proc filtered_hal {argl} {
        if {[llength $argl] == 0 || [string match --* [lindex $argl 0]]} {
            return [uplevel 2 [linsert $argl 0 ::compat::real::hal]]
        }
        set answer [ask $argl]
        switch -- [lindex $answer 0] {
            keep {
                return [uplevel 2 [linsert $argl 0 ::compat::real::hal]]
            }
            remove {
                return ""
            }
            rewrite {
                return [uplevel 2 [linsert [lrange $answer 1 end] 0 ::compat::real::hal]]
            }
        }
        error "compat: unexpected answer '$answer'"
    }

    # Every HAL command goes through the filter.
    proc install {} {
        foreach name [::hal --commands] {
            if {[info commands ::$name] eq "" || $name in {list gets source}} {
                continue
            }
            rename ::$name ::compat::real::$name
            proc ::$name {args} "::compat::filtered [list $name] \$args"
        }
        rename ::hal ::compat::real::hal
        proc ::hal {args} {::compat::filtered_hal $args}
    }
}
