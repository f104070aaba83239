# SPDX-License-Identifier: GPL-2.0-or-later
"""The "a test that cannot run fails" rules, proved on deliberately incomplete
situations: small fixture test trees run by a separate pytest with the skip
guard (tests/common/skipguard.py), and a CMake configure without Verilator.

Each fixture tree is its own rootdir (an empty pytest.ini), so only the
plugin under test is involved, not the project's conftest files.
"""

from __future__ import annotations

import json
import re
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
COMMON = ROOT / "tests" / "common"
sys.path.insert(0, str(COMMON))
from skipguard import AllowListError, area_of, parse_allow_list  # noqa: E402


def run_tree(
    tmp: Path, files: dict[str, str], skips: str = "", extra: list[str] | None = None
) -> subprocess.CompletedProcess[str]:
    """Write files under tmp/tree, the allow-list to tmp/skips.txt, run pytest."""
    tree = tmp / "tree"
    for name, text in files.items():
        p = tree / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    (tree / "pytest.ini").write_text("[pytest]\n")
    (tmp / "skips.txt").write_text(skips)
    env = dict(os.environ, PYTHONPATH=str(COMMON))
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-p",
            "skipguard",
            "-p",
            "no:cacheprovider",
            "-rs",
            f"--skips-file={tmp / 'skips.txt'}",
            "--rootdir",
            str(tree),
            "-c",
            str(tree / "pytest.ini"),
            *(extra or []),
            str(tree),
        ],
        cwd=tree,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )


PASSING = "def test_ok():\n    assert 1 + 1 == 2\n"
SKIPPING = "import pytest\n\ndef test_gone():\n    pytest.skip('part X not built')\n"


def test_unlisted_skip_fails_the_session(tmp_path: Path) -> None:
    r = run_tree(tmp_path, {"tests/a/test_a.py": PASSING + SKIPPING})
    assert r.returncode == 1, r.stdout
    assert "UNLISTED SKIP tests/a/test_a.py::test_gone: part X not built" in r.stdout
    assert "1 passed, 1 skipped" in r.stdout
    # -rs puts the skip and its reason in the log
    assert "SKIPPED [1] tests/a/test_a.py:6: part X not built" in r.stdout


def test_listed_skip_passes(tmp_path: Path) -> None:
    r = run_tree(
        tmp_path,
        {"tests/a/test_a.py": PASSING + SKIPPING},
        "skip tests/a/test_a.py::test_gone  needs hardware this machine lacks\n",
    )
    assert r.returncode == 0, r.stdout
    assert "skip guard" not in r.stdout


def test_pattern_star_and_literal_brackets(tmp_path: Path) -> None:
    src = (
        "import pytest\n\n@pytest.mark.parametrize('n', [1, 2])\n"
        "def test_p(n):\n    pytest.skip('no')\n"
    )
    ok = run_tree(
        tmp_path / "ok", {"tests/a/test_p.py": src}, "skip tests/a/test_p.py::test_p[*]  r\n"
    )
    assert ok.returncode == 0, ok.stdout
    # `[12]` is not a character class: it matches neither test_p[1] nor test_p[2]
    bad = run_tree(
        tmp_path / "bad", {"tests/a/test_p.py": src}, "skip tests/a/test_p.py::test_p[12]  r\n"
    )
    assert bad.returncode == 1
    assert bad.stdout.count("UNLISTED SKIP") == 2


def test_stale_skip_entry_fails(tmp_path: Path) -> None:
    r = run_tree(
        tmp_path, {"tests/a/test_a.py": PASSING}, "skip tests/a/test_a.py::test_ok  was flaky\n"
    )
    assert r.returncode == 1, r.stdout
    assert "STALE ENTRY" in r.stdout and "test_ok" in r.stdout


def test_module_level_skip_and_importorskip_fail(tmp_path: Path) -> None:
    r = run_tree(
        tmp_path,
        {
            "tests/a/test_mod.py": "import pytest\npytest.skip('x', allow_module_level=True)\n",
            "tests/b/test_imp.py": "import pytest\npytest.importorskip('no_such_module_hm')\n",
            "tests/c/test_c.py": PASSING,
        },
    )
    assert r.returncode == 1, r.stdout
    assert "UNLISTED SKIP tests/a/test_mod.py" in r.stdout
    assert "UNLISTED SKIP tests/b/test_imp.py" in r.stdout


def test_requires_build_missing_fails_not_skips(tmp_path: Path) -> None:
    src = (
        "import pytest\n\n"
        f"@pytest.mark.requires_build({str(tmp_path / 'build' / 'bin' / 'vboard')!r})\n"
        "def test_board():\n    pass\n"
    )
    r = run_tree(tmp_path, {"tests/vb/test_vb.py": src})
    assert r.returncode == 1, r.stdout
    assert "required part not built:" in r.stdout and "bin/vboard" in r.stdout
    assert "1 error" in r.stdout and "skipped" not in r.stdout
    (tmp_path / "build" / "bin").mkdir(parents=True)
    (tmp_path / "build" / "bin" / "vboard").write_text("")
    r = run_tree(tmp_path, {"tests/vb/test_vb.py": src})
    assert r.returncode == 0, r.stdout


def test_unlisted_xfail_fails(tmp_path: Path) -> None:
    src = "import pytest\n\n@pytest.mark.xfail(reason='later')\ndef test_x():\n    assert 0\n"
    r = run_tree(tmp_path, {"tests/a/test_x.py": src})
    assert r.returncode == 1, r.stdout
    assert "UNLISTED SKIP tests/a/test_x.py::test_x: xfail: later" in r.stdout


def test_pending_runs_as_strict_xfail(tmp_path: Path) -> None:
    failing = "def test_doc():\n    raise RuntimeError('component pid not found')\n"
    entry = "pending tests/d/test_d.py::test_doc  uses pid, not written yet\n"
    r = run_tree(tmp_path / "f", {"tests/d/test_d.py": failing}, entry)
    assert r.returncode == 0, r.stdout
    assert "1 xfailed" in r.stdout
    assert "uses pid, not written yet" in r.stdout  # the pending list in the summary
    # the component landed: the example passes, the entry must go
    r = run_tree(
        tmp_path / "p", {"tests/d/test_d.py": PASSING.replace("test_ok", "test_doc")}, entry
    )
    assert r.returncode == 1, r.stdout
    assert "XPASS(strict)" in r.stdout


def test_area_report(tmp_path: Path) -> None:
    out = tmp_path / "areas.json"
    r = run_tree(
        tmp_path,
        {
            "tests/hal/test_h.py": PASSING + "\ndef test_bad():\n    assert 0\n",
            "tests/e2e/hm2/test_e.py": PASSING + SKIPPING,
        },
        "skip tests/e2e/hm2/test_e.py::test_gone  reason\n",
        [f"--area-report={out}"],
    )
    assert r.returncode == 1, r.stdout  # test_bad
    data = json.loads(out.read_text())
    assert data["areas"]["hal"] == {
        "passed": 1,
        "failed": 1,
        "skipped": 0,
        "xfailed": 0,
        "errors": 0,
    }
    assert data["areas"]["e2e"] == {
        "passed": 1,
        "failed": 0,
        "skipped": 1,
        "xfailed": 0,
        "errors": 0,
    }
    assert data["unlisted"] == [] and data["stale"] == []


def test_allow_list_syntax(tmp_path: Path) -> None:
    f = tmp_path / "s.txt"
    f.write_text("# comment\n\nskip tests/x.py::t  a reason with spaces\n")
    (e,) = parse_allow_list(f)
    assert (e.kind, e.pattern, e.reason) == ("skip", "tests/x.py::t", "a reason with spaces")
    for bad in ("skip tests/x.py::t\n", "maybe tests/x.py::t why\n"):
        f.write_text(bad)
        with pytest.raises(AllowListError, match=f"{f}:1"):
            parse_allow_list(f)
    # a malformed list stops the run with a usage error, naming the line
    r = run_tree(tmp_path, {"tests/a/test_a.py": PASSING}, "skip tests/a/test_a.py::test_ok\n")
    assert r.returncode == 4 and "skips.txt:1: expected 'KIND PATTERN REASON'" in r.stderr


def test_project_allow_list_parses() -> None:
    for e in parse_allow_list(ROOT / "tests" / "skips.txt"):
        assert e.reason and e.pattern.startswith("tests/"), e


def test_area_of() -> None:
    assert area_of("tests/e2e/hm2/test_x.py::t[a/b]") == "e2e"
    assert area_of("tests/hal/test_hal_regression.py::test_hal[and2]") == "hal"


def test_cmake_without_verilator_fails_naming_it(tmp_path: Path) -> None:
    """The virtual board is required: configuring without Verilator stops with
    a message saying how to get it (it used to drop bin/vboard quietly)."""
    env = {k: v for k, v in os.environ.items() if k != "VERILATOR_ROOT"}
    r = subprocess.run(
        ["cmake", "-S", str(ROOT), "-B", str(tmp_path / "b")],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode != 0
    err = " ".join(r.stderr.split())
    assert "Verilator is required but VERILATOR_ROOT is not set" in err
    assert "make deps" in err


def _summary(tmp: Path, areas: dict[str, dict[str, int]], junit: str, *extra: str) -> str:
    tests = tmp / "tests"
    for a in ("hal", "e2e"):
        (tests / a).mkdir(parents=True, exist_ok=True)
        (tests / a / "test_x.py").write_text("")
    (tmp / "areas.json").write_text(json.dumps({"areas": areas, "unlisted": [], "stale": []}))
    (tmp / "ctest.xml").write_text(junit)
    r = subprocess.run(
        [
            sys.executable,
            str(ROOT / "scripts" / "test_summary.py"),
            "--tests",
            str(tests),
            "--ctest",
            str(tmp / "ctest.xml"),
            "--areas",
            str(tmp / "areas.json"),
            "--ctest-rc",
            "0",
            "--pytest-rc",
            "0",
            *extra,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )
    return f"rc={r.returncode}\n{r.stdout}{r.stderr}"


JUNIT_OK = (
    '<testsuite><testcase name="a" status="run"/><testcase name="b" status="run"/></testsuite>'
)
ONE = {"passed": 1, "failed": 0, "errors": 0, "skipped": 0, "xfailed": 0}


def test_summary_counts_every_area(tmp_path: Path) -> None:
    out = _summary(tmp_path, {"hal": ONE, "e2e": ONE}, JUNIT_OK)
    assert out.startswith("rc=0"), out
    assert re.search(r"C units \(ctest\)\s+2\s+0", out), out
    assert re.search(r"HAL regression\s+1\s+0", out) and re.search(r"e2e\s+1\s+0", out), out
    assert out.rstrip().endswith("make test: ok"), out


def test_summary_fails_on_a_lost_area(tmp_path: Path) -> None:
    """tests/e2e exists but ran nothing (e.g. its files stopped being collected)."""
    out = _summary(tmp_path, {"hal": ONE}, JUNIT_OK)
    assert out.startswith("rc=1"), out
    assert re.search(r"e2e\s+0\s+0\s+0\s+0\s+0\s+LOST", out), out
    assert "FAIL: area e2e (tests/e2e) ran no passing test" in out
    # a narrowed run (PYTEST_ARGS) only notes it
    assert _summary(tmp_path, {"hal": ONE}, JUNIT_OK, "--narrowed").startswith("rc=0")


def test_summary_fails_on_ctest_not_run(tmp_path: Path) -> None:
    junit = '<testsuite><testcase name="a" status="run"/><testcase name="b" status="notrun"/></testsuite>'
    out = _summary(tmp_path, {"hal": ONE, "e2e": ONE}, junit)
    assert out.startswith("rc=1") and "ctest: 1 test(s) not run" in out, out
