# SPDX-License-Identifier: GPL-2.0-or-later
# A userspace component in Python: out = in * gain, count of passes; ends
# on SIGTERM (halcmd unload) through KeyboardInterrupt.
import time

import hal

c = hal.component("pycomp")
c.newpin("in", hal.HAL_FLOAT, hal.HAL_IN)
c.newpin("out", hal.HAL_FLOAT, hal.HAL_OUT)
c.newpin("enable", hal.HAL_BIT, hal.HAL_IN)
c.newpin("ticks", hal.HAL_U32, hal.HAL_OUT)
c.newparam("gain", hal.HAL_FLOAT, hal.HAL_RW)
c.newparam("version", hal.HAL_S32, hal.HAL_RO)
c["gain"] = 2.0
c.version = 3
c.setprefix("pycomp.sub")
c.newpin("flag", hal.HAL_BIT, hal.HAL_OUT)
c.ticks = 1
c.ready()
try:
    while True:
        if c.enable:
            c.out = c["in"] * c.gain
            c.flag = c.out > 10
        time.sleep(0.005)
except KeyboardInterrupt:
    pass
