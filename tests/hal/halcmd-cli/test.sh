# SPDX-License-Identifier: GPL-2.0-or-later
# halcmd used on its own, one command per invocation, as scripts do;
# -s (no headers), -f - (stdin), -Q, exit codes.
halcmd loadrt and2 count=2
halcmd net x and2.0.out and2.1.in0; echo "net rc=$?"
halcmd -s show pin and2.1.in0
halcmd getp and2.0.in0
halcmd setp and2.0.in0 2; echo "setp rc=$?"
printf 'setp and2.0.in0 1\ngetp and2.0.in0\n' | halcmd -f
halcmd -Q getp nosuch; echo "Q rc=$?"
halcmd list sig
halcmd bogus 2>&1; echo "bogus rc=$?"
halcmd stop
halcmd unload all
sleep 0.2
halcmd --session-rtapi-alive; echo "rtapi alive rc=$?"
halcmd --session-destroy
# halrun -I: interactive halcmd after the file (here fed from a pipe)
printf 'list sig\nnewsig late bit\nlist sig\n' | halrun -I x.hal; echo "halrun -I rc=$?"
