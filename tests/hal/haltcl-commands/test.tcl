# SPDX-License-Identifier: GPL-2.0-or-later
# haltcl: halcmd's commands as Tcl commands, their results as Tcl values,
# setp/sets values as Tcl expressions, procedures and loops making HAL
# objects, errors caught with catch (a failed command's message ends with
# halcmd's error line; LinuxCNC puts its -v lines before it, so only the
# last line is compared).  expected captured from LinuxCNC 2.9's
# halrun (lcnc-halrun test.tcl), normalized by halnorm.py.
loadrt and2 count=3
loadrt scale count=2
loadrt threads name1=t period1=1000000
proc chain {n} {
    for {set i 0} {$i < $n} {incr i} {
        net link-$i and2.$i.out and2.[expr {$i + 1}].in0
        addf and2.$i t
    }
}
chain 2
setp scale.0.gain 1.5*2
setp scale.1.gain [expr {atan(1) * 4}]
puts "gain0=[getp scale.0.gain]"
puts "gain1=[getp scale.1.gain]"
setp and2.0.in0 1
puts "ptype=[ptype and2.0.in0] stype=[stype link-0]"
puts "pins=[hal list pin and2.1]"
puts "sigs=[lsort [hal list sig]]"
set shown [hal show pin and2.0.in0]
puts "shown has [llength [split $shown \n]] lines"
newsig spare float
sets spare 2.5/2
puts "spare=[hal gets spare]"
puts "tcl list is Tcl's: [list a {b c}]"
foreach p {in0 in1} {
    puts "and2.2.$p=[getp and2.2.$p]"
}
proc last {msg} { return [lindex [split $msg \n] end] }
puts "missing pin: [catch {setp and2.0.nosuch 1} msg] <[last $msg]>"
puts "bad value: [catch {setp and2.0.in1 7} msg] <[lrange [split $msg \n] end-1 end]>"
puts "type mismatch: [catch {net link-0 scale.0.in} msg] <[last $msg]>"
puts "no such comp: [catch {loadrt nosuch_comp_xyz} msg]"
puts "unknown: [catch {hal frobnicate} msg] <$msg>"
puts "usage: [catch {setp a} msg] [string match {wrong # args: should be "setp *"} $msg]"
puts "in1 still [getp and2.0.in1], link-0 still [hal list sig link-0]"
show sig link
