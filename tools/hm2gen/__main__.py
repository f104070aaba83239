# SPDX-License-Identifier: GPL-2.0-or-later
"""Command line: ``python -m hm2gen`` (or the ``hm2gen`` wrapper in bin/)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .emit import write_all
from .model import DescriptionError, Firmware, load_firmware


def _all_firmwares(root: Path) -> list[Path]:
    fws = sorted((root / "firmware").glob("*/*.toml"))
    if not fws:
        raise DescriptionError(f"{root / 'firmware'}: no firmware descriptions found")
    return fws


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        prog="hm2gen",
        description="Generate the Verilog include and top, IDROM image, .PIN file and JSON "
        "of HostMot2 firmware descriptions.",
    )
    ap.add_argument("firmware", nargs="*", type=Path, help="firmware description(s) (.toml)")
    ap.add_argument(
        "--all",
        metavar="ROOT",
        type=Path,
        help="every ROOT/firmware/<board>/<name>.toml (ROOT is hdl/hostmot2)",
    )
    ap.add_argument(
        "-o", "--out", type=Path, help="output directory; outputs go to OUT/<board>/<firmware>/"
    )
    ap.add_argument(
        "--boards",
        type=Path,
        help="board description directory " "(default: ../../boards next to each firmware file)",
    )
    ap.add_argument("--check", action="store_true", help="validate only, write nothing")
    ap.add_argument("-q", "--quiet", action="store_true")
    args = ap.parse_args(argv)

    try:
        paths = list(args.firmware)
        if args.all is not None:
            paths += _all_firmwares(args.all)
        if not paths:
            ap.error("no firmware description given (name files or use --all)")
        if not args.check and args.out is None:
            ap.error("-o/--out is required unless --check is given")
        # Validate everything before writing anything.
        fws: list[Firmware] = [load_firmware(p, args.boards) for p in paths]
        names = [(f.board.name, f.name) for f in fws]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise DescriptionError(f"firmware given twice: {sorted(dup)}")
        for fw in fws:
            if args.check:
                if not args.quiet:
                    print(
                        f"hm2gen: {fw.source}: ok ({fw.board.name} {fw.name}, "
                        f"{len(fw.md_table)} modules, {fw.board.io_width} pins)"
                    )
                continue
            out = write_all(fw, args.out / fw.board.name / fw.name)
            if not args.quiet:
                print(f"hm2gen: {fw.board.name}/{fw.name} -> {out['json'].parent}")
    except DescriptionError as e:
        print(f"hm2gen: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
