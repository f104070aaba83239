# SPDX-License-Identifier: GPL-2.0-or-later
"""halcompile (also installed as comp): the HAL component generator.

    halcompile [--preprocess] [-o OUT.c] FILE.comp       FILE.comp -> NAME.c
    halcompile --compile [-o OUT] FILE.comp|FILE.c       -> NAME.so (userspace: NAME)
    halcompile --install [--user] FILE.comp|FILE.c       compile and install
    halcompile --document [-o OUT.md] FILE.comp          man page (docs/ markdown)
    halcompile --print-modinfo FILE.comp                 what the module offers
    halcompile --compile --userspace FILE.c              a userspace program from C
    halcompile --install --userspace FILE.py             a Python component as a program

See docs/halcompile.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from . import build
from .check import check, stem
from .gen_c import generate
from .model import Component
from .parser import parse_file
from .scanner import CompError


def load(path: Path, in_tree: bool = False) -> Component:
    """Parse and check.  Outputs are named after the component (the seed:
    `comp --compile rtexample.comp` leaves example.so); in the source tree
    the file must carry the component's name."""
    comp = parse_file(path)
    comp.source = path
    check(comp, expect_name=stem(path) if in_tree else None)
    return comp


def write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def preprocess(path: Path, out: Path) -> Component:
    comp = load(path)
    write_atomic(out, generate(comp, str(path), str(out)))
    return comp


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="halcompile",
        description="Generate, compile, install and document HAL components (.comp files).",
    )
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--preprocess", action="store_true", help="write NAME.c (the default)")
    mode.add_argument("-c", "--compile", action="store_true", help="build NAME.so or NAME")
    mode.add_argument("--install", action="store_true", help="build and install")
    mode.add_argument("--document", action="store_true", help="write the man page NAME.md")
    mode.add_argument("--print-modinfo", action="store_true", help="print module information")
    mode.add_argument("--kind", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--user", action="store_true", help="with --install: into the user folder")
    p.add_argument("-u", "--userspace", action="store_true", help=".c files: build a program")
    p.add_argument("-o", "--output", type=Path, help="output file (one input only)")
    p.add_argument("--expect-kind", choices=("rt", "user"), help=argparse.SUPPRESS)
    p.add_argument("--kind-stamp", type=Path, help=argparse.SUPPRESS)
    p.add_argument("--extra-compile-args", default="", help="more compiler flags")
    p.add_argument("--extra-link-args", default="", help="more linker flags")
    p.add_argument("files", nargs="+", type=Path, metavar="FILE")
    return p


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.output is not None and len(args.files) > 1:
        print("halcompile: error: -o needs exactly one input file", file=sys.stderr)
        return 2
    if args.user and not args.install:
        print("halcompile: error: --user goes with --install", file=sys.stderr)
        return 2
    if args.kind:
        return _kinds(args.files)
    status = 0
    for f in args.files:
        try:
            _one(args, f)
        except CompError as e:
            print(e, file=sys.stderr)
            status = 1
        except build.BuildError as e:
            print(f"halcompile: error: {e}", file=sys.stderr)
            status = 1
        except OSError as e:
            print(f"halcompile: error: {f}: {e.strerror or e}", file=sys.stderr)
            status = 1
    return status


def _kinds(files: list[Path]) -> int:
    """For the build system: 'NAME rt' or 'NAME user' per file.  A file that
    does not parse is reported as rt; compiling it reports the error."""
    for f in files:
        kind = "rt"
        try:
            if parse_file(f).userspace:
                kind = "user"
        except (CompError, OSError):
            pass
        print(f"{stem(f)} {kind}")
    return 0


def _one(args: argparse.Namespace, f: Path) -> None:
    from .document import document  # noqa: PLC0415 (keeps start-up light)
    from .modinfo import modinfo  # noqa: PLC0415

    if not f.exists():
        raise OSError(2, f"{f}: no such file")
    if f.suffix == ".py":
        _install_python(args, f)
        return
    is_c = f.suffix == ".c"
    if is_c and not (args.compile or args.install):
        raise build.BuildError(f"{f}: a .c file can only be compiled or installed")
    if args.document:
        comp = load(f)
        out = args.output or Path(f"{comp.name}.md")
        write_atomic(out, document(comp))
        return
    if args.print_modinfo:
        print(modinfo(load(f)), end="")
        return
    if not (args.compile or args.install):
        comp = load(f, in_tree=args.expect_kind is not None)
        if args.expect_kind and args.expect_kind != ("user" if comp.userspace else "rt"):
            if args.kind_stamp is not None:
                args.kind_stamp.write_text(f"{comp.name} changed kind\n")
            raise build.BuildError(
                f"{f}: 'option userspace' changed since the build was configured; "
                "build again (the next build re-configures)"
            )
        preprocess(f, args.output or Path(f"{comp.name}.c"))
        return
    _compile_install(args, f, is_c)


def _install_python(args: argparse.Namespace, f: Path) -> None:
    """LinuxCNC's `halcompile --install --userspace file.py`: the script
    becomes the program NAME (no .py) in the bin folder."""
    if not (args.install and args.userspace):
        raise build.BuildError(f"{f}: a Python file can only be installed with --userspace")
    cfg = build.Config.from_env()
    dest = cfg.user_bindir() if args.user else cfg.bindir
    final = build.install_file(f, dest, stem(f), 0o755)
    print(f"halcompile: installed {final}")


def _compile_install(args: argparse.Namespace, f: Path, is_c: bool) -> None:
    import shlex

    cfg = build.Config.from_env()
    extra_c = shlex.split(args.extra_compile_args)
    extra_l = shlex.split(args.extra_link_args)
    with tempfile.TemporaryDirectory(prefix="halcompile.") as td:
        tmp = Path(td)
        if is_c:
            name, userspace, csrc = stem(f), args.userspace, f
        else:
            comp = load(f)
            name, userspace = comp.name, comp.userspace
            csrc = tmp / f"{name}.c"
            csrc.write_text(generate(comp, str(f.resolve()), str(csrc)))
            # `include "x.h";` and #include "x.h" find headers next to the .comp
            extra_c += [f"-I{f.resolve().parent}"]
            extra_c += shlex.split(comp.options.get("extra_compile_args", ""))
            extra_l += shlex.split(comp.options.get("extra_link_args", ""))
        fname = name if userspace else f"{name}.so"
        built = tmp / fname
        build.compile_c(cfg, csrc, built, userspace, extra_c, extra_l)
        if args.install:
            if args.user:
                dest = cfg.user_bindir() if userspace else cfg.user_rtlib()
            else:
                dest = cfg.bindir if userspace else cfg.rtlib
            final = build.install_file(built, dest, fname, 0o755)
            print(f"halcompile: installed {final}")
        else:
            out = args.output or Path(fname)
            build.install_file(built, out.parent if str(out.parent) else Path("."), out.name, 0o755)
