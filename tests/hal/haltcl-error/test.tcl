# SPDX-License-Identifier: GPL-2.0-or-later
# haltcl: a HAL command that fails ends the script there with exit status
# 1 (what ran before stays); halrun still ends the session.  expected
# (stdout) and exitcode captured from LinuxCNC 2.9's halrun
# (lcnc-halrun test.tcl); the error message on stderr is our own form,
# FILE:LINE: message.
loadrt and2 count=1
proc connect {pin} {
    net out-sig and2.0.out $pin
}
setp and2.0.in0 1
puts "before: [getp and2.0.in0]"
connect and2.0.in1
puts "linked: [hal list sig]"
connect and2.0.nosuch
puts "never printed"
