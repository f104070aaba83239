# SPDX-License-Identifier: GPL-2.0-or-later
"""Every example in docs/*.md, README.md and examples/**/README.md runs
(rules: tests/docs/docex.py).

Examples that cannot work yet (a component not written yet) are listed as
``pending`` in tests/skips.txt with the reason: they still run, and the day
one passes the run fails until its entry is removed.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALRUN = BUILD / "bin" / "halrun"
VBOARD = BUILD / "bin" / "vboard"
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT / "tests" / "common"))
import docex  # noqa: E402
import vboard  # noqa: E402

PAGES = (
    sorted((ROOT / "docs").glob("*.md"))
    + [ROOT / "README.md"]
    + sorted((ROOT / "examples").glob("**/README.md"))
)


def _name(page: Path) -> str:
    """docs/X.md -> X.md; other pages by their path (README.md,
    examples/machines/README.md)."""
    return page.name if page.parent == ROOT / "docs" else str(page.relative_to(ROOT))


def _all_examples() -> list[docex.Example]:
    out: list[docex.Example] = []
    for page in PAGES:
        try:
            out += docex.examples(page, _name(page))
        except docex.DocError:
            pass  # reported by test_page_follows_the_rules
    return out


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_page_follows_the_rules(page: Path) -> None:
    """Examples are runnable blocks; directives and output blocks are well placed."""
    error = None
    try:
        docex.examples(page, _name(page))
    except docex.DocError as e:
        error = str(e)
    if error:
        pytest.fail(error, pytrace=False)


def _sanitizer_env() -> dict[str, str]:
    """With a sanitized build the Python hal module needs the ASan runtime
    preloaded into the (uninstrumented) interpreter."""
    ext = next((BUILD / "lib" / "python").glob("_hal*.so"), None)
    if ext is None:
        return {}
    ldd = subprocess.run(["ldd", str(ext)], capture_output=True, text=True).stdout
    libs = [
        line.split("=>")[1].split()[0]
        for line in ldd.splitlines()
        if "=>" in line and ("libasan" in line or "libubsan" in line)
    ]
    return {"LD_PRELOAD": " ".join(libs), "ASAN_OPTIONS": "detect_leaks=0"} if libs else {}


@pytest.fixture
def private() -> Iterator[Path]:
    # Short: socket paths (sun_path) are limited to 108 bytes.
    d = Path(tempfile.mkdtemp(prefix="dx"))
    yield d
    shutil.rmtree(d, ignore_errors=True)


def _start_board(args: list[str]) -> vboard.VBoardProcess:
    sock, board, rest = None, None, []
    it = iter(args)
    for a in it:
        if a == "--socket":
            sock = next(it)
        elif a == "--board":
            board = next(it)
        else:
            rest.append(a)
    assert sock and board, f"vboard directive needs --socket and --board: {args}"
    return vboard.VBoardProcess(sock, board, None, rest)


def _run(ex: docex.Example, private: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    text = ex.text.replace("/tmp/", f"{private}/")
    if ex.lang == "hal":
        f = private / "example.hal"
        f.write_text(text)
        cmd = [str(HALRUN), *ex.halrun, "-f", str(f)]
    elif ex.lang == "sh":
        f = private / "example.sh"
        f.write_text("set -e\n" + text)
        cmd = ["bash", str(f)]
    else:
        f = private / "example.py"
        f.write_text(text)
        cmd = [sys.executable, str(f)]
    proc = subprocess.Popen(
        cmd,
        cwd=ROOT,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        out, err = proc.communicate(timeout=180)
    finally:
        # background jobs the example started (`vboard ... &`) end with it
        try:
            os.killpg(proc.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


@pytest.mark.requires_build(HALRUN, VBOARD)
@pytest.mark.parametrize("ex", [pytest.param(e, id=e.id) for e in _all_examples()])
def test_example(ex: docex.Example, private: Path) -> None:
    """The example exits as documented and prints its output block."""
    if ex.hardware:
        pytest.skip(f"needs hardware: {ex.hardware}")
    home = private / "home"
    home.mkdir()
    env = dict(os.environ)
    env.pop("HAL_SIMCLOCK", None)
    env.update(
        HAL_INSTANCE=f"doc-{uuid.uuid4().hex[:10]}",
        HOME=str(home),
        HM_BUILD=str(BUILD),
        HM_ROOT=str(ROOT),
        PATH=f"{BUILD / 'bin'}:{ROOT / '.venv' / 'bin'}:{env.get('PATH', '')}",
        PYTHONPATH=str(BUILD / "lib" / "python"),
    )
    if ex.lang == "python":
        env.update(_sanitizer_env())
    env.update({k: v.replace("/tmp/", f"{private}/") for k, v in ex.env.items()})
    boards = []
    try:
        for args in ex.vboards:
            boards.append(_start_board([a.replace("/tmp/", f"{private}/") for a in args]))
        r = _run(ex, private, env)
    finally:
        for b in boards:
            b.stop()
        subprocess.run([str(HALRUN), "-U"], env=env, capture_output=True, timeout=60)
    log = f"--- {ex.id} ({ex.lang}), exit {r.returncode}\n--- stdout:\n{r.stdout}--- stderr:\n{r.stderr}"
    assert r.returncode == ex.exit, log
    assert "Sanitizer" not in r.stderr, log
    if ex.output is not None:
        want = ex.output.replace("/tmp/", f"{private}/")
        assert docex.output_matches(r.stdout, want), f"output differs from the page\n{log}"


def test_rules_on_a_sample_page(tmp_path: Path) -> None:
    """The extractor itself: kinds, directives, output blocks, example sections."""
    page = tmp_path / "x.md"
    page.write_text(
        "# x\n\n## SYNOPSIS\n\n    loadrt x [count=N]\n\n```\nnot run\n```\n\n"
        "## EXAMPLES\n\n<!-- test: exit 1; vboard --socket /tmp/s --board 5i20 -->\n"
        "Text.\n\n```hal\nloadrt nothing\n```\n\n```output\nline\n...\n```\n\n"
        "```sh\necho hi\n```\n"
    )
    a, b = docex.examples(page)
    assert (a.lang, a.line, a.exit, a.output) == ("hal", 16, 1, "line\n...\n")
    assert a.vboards == [["--socket", "/tmp/s", "--board", "5i20"]]
    assert (b.lang, b.exit, b.vboards, b.output) == ("sh", 0, [], None)
    for bad, msg in (
        ("## Example\n\n    halrun -f x.hal\n", "is not run"),
        ("## Example\n\n```\nx\n```\n", "is not run"),
        ("text\n\n```output\nx\n```\n", "must follow an example"),
        ("<!-- test: frobnicate -->\n```hal\nx\n```\n", "unknown test directive"),
        ("<!-- test: exit 1 -->\n```c\nx\n```\n", "not run"),
        ("```hal\nx\n", "not closed"),
    ):
        page.write_text(bad)
        with pytest.raises(docex.DocError, match=msg):
            docex.examples(page)
    # a list item's indented continuation is not a code block
    page.write_text("## Examples\n\n- item\n\n    continued item text\n")
    assert docex.examples(page) == []


def test_output_matching() -> None:
    assert docex.output_matches("a\nb  \n", "a\nb\n")
    assert docex.output_matches("a\nx\ny\nb\n", "a\n...\nb\n")
    assert docex.output_matches("a\nb\n", "a\n...\nb\n")
    assert not docex.output_matches("a\nc\n", "a\n...\nb\n")
    assert not docex.output_matches("a\nb\nc\n", "a\nb\n")
    assert not docex.output_matches("", "a\n")


@pytest.mark.requires_build(HALRUN, VBOARD, BUILD / "lib" / "rtlib" / "hm2_sim.so")
def test_make_demo(private: Path) -> None:
    """`make demo` (README's first command; scripts/demo.sh without the build
    step): the stepgen reaches the commanded 0.25 within a step and the
    encoder counted every step that came out of the looped pins."""
    env = dict(os.environ, HM_BUILD=str(BUILD), HOME=str(private))
    env.pop("HAL_SIMCLOCK", None)
    r = subprocess.run(
        ["bash", str(ROOT / "scripts" / "demo.sh")],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    log = f"--- stdout:\n{r.stdout}--- stderr:\n{r.stderr}"
    assert r.returncode == 0, log
    assert "Sanitizer" not in r.stderr, log
    assert "hm2/hm2_5i20.0:     IO Pin 048 (P4-01): StepGen #0, pin Step (Output)" in r.stdout, log
    steps = [line for line in r.stdout.splitlines() if line.strip().startswith("steps generated")]
    assert len(steps) == 1, log
    words = steps[0].replace(",", "").split()
    generated, counted = int(words[2]), int(words[-1])
    assert abs(generated - 250) <= 1 and counted == generated, log
