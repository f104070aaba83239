# SPDX-License-Identifier: GPL-2.0-or-later
# the userspace "peer": after a moment, run one halcmd command
sleep 0.3
halcmd "$@"
