# SPDX-License-Identifier: GPL-2.0-or-later
# The component search path (docs/rtapi.md): $HAL_RTLIB_PATH, then
# $HOME/.local/lib/hm2stack/rtlib, then the build's lib/rtlib; a name with
# '/' or '..' is refused.  Stand-ins: or2.so copied as and2.so shows which
# directory won (loadrt and2 then makes an `or2` component).
exec 2>&1
t=$(mktemp -d)
trap 'halrun -U >/dev/null 2>&1; rm -rf "$t"' EXIT
rtlib=$HM_BUILD/lib/rtlib
mkdir -p "$t/p1" "$t/p2" "$t/home/.local/lib/hm2stack/rtlib"
cp "$rtlib/or2.so" "$t/p2/and2.so"
cp "$rtlib/not.so" "$t/home/.local/lib/hm2stack/rtlib/and2.so"
cp "$rtlib/xor2.so" "$t/home/.local/lib/hm2stack/rtlib/usercomp.so"
unset HAL_RTLIB_DIR
cd "$t" || exit 1
printf 'loadrt and2\nloadrt usercomp\nlist comp\n' > a.hal
echo "== HAL_RTLIB_PATH first (empty and missing dirs skipped)"
HOME=$t/home HAL_RTLIB_PATH="$t/nonexistent::$t/p1:$t/p2" halrun -f a.hal
echo "== then the user folder"
HOME=$t/home HAL_RTLIB_PATH= halrun -f a.hal
echo "== then the build"
printf 'loadrt and2\nlist comp\n' > b.hal
HOME=$t/home-without-comps halrun -f b.hal
echo "== refused names"
printf 'loadrt ../rtlib/and2\nloadrt %s/and2\nloadrt a..b\nloadrt nosuchcomp\nlist comp\n' \
    "$rtlib" > c.hal
halrun -k -f c.hal; echo "rc=$?"
