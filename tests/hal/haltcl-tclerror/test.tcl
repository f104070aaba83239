# SPDX-License-Identifier: GPL-2.0-or-later
# haltcl: a Tcl error (not a HAL command's) also ends the script with exit
# status 1; the message names the file and line, then Tcl's trace.
# expected and exitcode captured from LinuxCNC 2.9's halrun
# (lcnc-halrun test.tcl); expected.stderr is our own form.
loadrt and2 count=1
proc ratio {a b} {
    return [expr {$a / $b}]
}
puts "ratio: [ratio 6 3]"
setp and2.0.in0 [ratio 1 0]
puts "never printed"
