// SPDX-License-Identifier: GPL-2.0-or-later
// hal_speaker: eight parallel-port-style output bits made audible as
// clicks of a PC speaker, LinuxCNC 2.9's pin and function names
// (docs/hal_speaker.md).  The speaker is simulated: where its cone is and
// how often it moved are parameters; no I/O port is touched.
component hal_speaker "Output bits heard as clicks of a (simulated) PC speaker";
pin in bit pin_02_out "Data bit 0: parallel-port pin 2";
pin in bit pin_03_out "Data bit 1: parallel-port pin 3";
pin in bit pin_04_out "Data bit 2: parallel-port pin 4";
pin in bit pin_05_out "Data bit 3: parallel-port pin 5";
pin in bit pin_06_out "Data bit 4: parallel-port pin 6";
pin in bit pin_07_out "Data bit 5: parallel-port pin 7";
pin in bit pin_08_out "Data bit 6: parallel-port pin 8";
pin in bit pin_09_out "Data bit 7: parallel-port pin 9";
param rw bit pin_02_out_invert "Invert pin-02-out before it reaches the speaker";
param rw bit pin_03_out_invert "Invert pin-03-out before it reaches the speaker";
param rw bit pin_04_out_invert "Invert pin-04-out before it reaches the speaker";
param rw bit pin_05_out_invert "Invert pin-05-out before it reaches the speaker";
param rw bit pin_06_out_invert "Invert pin-06-out before it reaches the speaker";
param rw bit pin_07_out_invert "Invert pin-07-out before it reaches the speaker";
param rw bit pin_08_out_invert "Invert pin-08-out before it reaches the speaker";
param rw bit pin_09_out_invert "Invert pin-09-out before it reaches the speaker";
param r bit cone "Where the simulated speaker's cone is: the parity of the eight bits after inversion";
param r u32 clicks "Cone movements since loading, two a step pulse (out and back); wraps at 2^32";
function write nofp "Move the cone to the parity of the bits, counting each move";
license "GPL";
;;

/* A step pulse changes one bit twice: the cone moves out and back, heard
 * as one click, whichever bit it is on. */
FUNCTION(write)
{
    int level = (pin_02_out != pin_02_out_invert) ^ (pin_03_out != pin_03_out_invert)
                ^ (pin_04_out != pin_04_out_invert) ^ (pin_05_out != pin_05_out_invert)
                ^ (pin_06_out != pin_06_out_invert) ^ (pin_07_out != pin_07_out_invert)
                ^ (pin_08_out != pin_08_out_invert) ^ (pin_09_out != pin_09_out_invert);
    if (level != (cone ? 1 : 0)) {
        cone = level;
        clicks++;
    }
}
