# SPDX-License-Identifier: GPL-2.0-or-later
# haltcl -i INI: each section a global array, each key's element the Tcl
# list of its values in file order (a repeated key has several), values
# trimmed and kept whole (quotes and trailing text included).  expected
# captured from LinuxCNC 2.9's halrun (lcnc-halrun -i test.ini test.tcl).
foreach s {EMCMOT JOINT_0 HOSTMOT2 HAL EMPTY NOSECTION} {
    puts "array $s: [array exists ::$s]"
}
puts "servo: $::EMCMOT(SERVO_PERIOD)"
puts "halfiles: [llength $::HAL(HALFILE)]"
foreach f $::HAL(HALFILE) {
    puts "  <$f>"
}
puts "driver: <$::HOSTMOT2(DRIVER)> config: <[lindex $::HOSTMOT2(CONFIG) 0]>"
puts "empty: <$::EMPTY(KEY)> [llength $::EMPTY(KEY)]"
puts "keys: [lsort [array names ::JOINT_0]]"
loadrt threads name1=servo period1=$::EMCMOT(SERVO_PERIOD)
loadrt scale count=1
setp scale.0.gain $::JOINT_0(P)*2
setp scale.0.offset 1.0/$::JOINT_0(SCALE)
puts "gain: [getp scale.0.gain] offset: [getp scale.0.offset]"
puts "period: [lindex [split [string trim [hal show thread servo]] \n] end]"
