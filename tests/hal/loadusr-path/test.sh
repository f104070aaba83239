# SPDX-License-Identifier: GPL-2.0-or-later
# loadusr finds the project's own programs first (halcmd's directory), then
# PATH: a program of the same name earlier on PATH is not the one started.
exec 2>&1
t=$(mktemp -d)
trap 'halrun -U >/dev/null 2>&1; rm -rf "$t"' EXIT
printf '#!/bin/sh\necho "the PATH impostor ran"\nexit 1\n' > "$t/hal_test_usercomp"
printf '#!/bin/sh\necho "a program only on PATH ran"\n' > "$t/only_on_path"
chmod +x "$t/hal_test_usercomp" "$t/only_on_path"
printf 'loadusr -Wn pathcomp hal_test_usercomp pathcomp\nlist comp\nloadusr -w only_on_path\nunloadusr pathcomp\n' > "$t/a.hal"
PATH="$t:$PATH" halrun -f "$t/a.hal" | sed -E 's/halcmd[0-9]+/halcmdN/'
echo "rc=${PIPESTATUS[0]}"
