// SPDX-License-Identifier: GPL-2.0-or-later
// The seed's "usrexample.comp" (content not shown there): a userspace
// component for loadusr that counts up while enable is TRUE.
component usrexample "counts up about once a millisecond while enable is TRUE";
option userspace;
pin in bit enable = 1;
pin out s32 out;
license "GPL";
;;
#include <unistd.h>

void user_mainloop(void) {
    for (;;) {
        FOR_ALL_INSTS() {
            if (enable)
                out++;
        }
        usleep(1000);
    }
}
