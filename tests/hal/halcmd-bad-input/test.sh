# SPDX-License-Identifier: GPL-2.0-or-later
# Hostile or broken input files: each must end with a clear error naming
# file:line and exit status 1, never a crash, a hang or silent success.
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
cd "$t" || exit 1
run() { # label, halrun args...
    local label=$1; shift
    timeout 60 halrun "$@" > out 2>&1
    echo "== $label rc=$?"
    cut -c1-300 out
}
# ~70,000 backslash-continued lines (once overflowed the heap)
python3 -c "import sys; sys.stdout.write('print a\\\\\n' * 70000 + 'b\n')" > cont.hal
run continuations -f cont.hal
# a line over 64 KiB (once skipped silently with exit 0)
python3 -c "import sys; sys.stdout.write('print a\nprint ' + 'x' * 70000 + '\nprint b\n')" > long.hal
run long-line -f long.hal
run long-line-k -k -f long.hal
# a line of exactly 65535 characters is still fine
python3 -c "import sys; sys.stdout.write('print ' + 'y' * 65529 + '\n')" > max.hal
timeout 60 halrun -f max.hal > out 2>&1; echo "== max-line rc=$? bytes=$(wc -c < out)"
# endless input without a newline, binary input, a directory
run dev-zero -f /dev/zero
printf 'print ok\nprint a\001\002\000b\n' > bin.hal
run binary -f bin.hal
mkdir adir
run directory -f adir
run missing -f nosuch.hal
# source loops and nesting
printf 'print in-self\nsource self.hal\n' > self.hal
run self-source -f self.hal
printf 'print in-a\nsource b.hal\n' > a.hal
printf 'print in-b\nsource a.hal\n' > b.hal
run loop -f a.hal
for i in $(seq 1 17); do echo "source n$((i + 1)).hal" > "n$i.hal"; done
echo "print deep" > n18.hal
run deep -f n1.hal
for i in $(seq 1 15); do echo "source m$((i + 1)).hal" > "m$i.hal"; done
echo "print sixteen-deep" > m16.hal
run sixteen -f m1.hal
echo "source adir" > srcdir.hal
run source-dir -f srcdir.hal
echo "== state $(halcmd --session-state)"
