# SPDX-License-Identifier: GPL-2.0-or-later
"""pytest plugin: a test that does not run fails the session, unless the skip
allow-list says why it may not run; plus a per-area count of the outcomes.

Loaded by tests/conftest.py for every run of the project's tests (and with
``-p skipguard`` by tests/infra, which runs it on small fixture trees).

Three things:

* ``@pytest.mark.requires_build(path, ...)``: the test needs these files of
  the build (binaries, modules, firmware).  A missing one is a *failure*
  naming the file, never a skip: a part that was not built must turn CI red.
* The allow-list (``tests/skips.txt``, option ``--skips-file``), one entry a
  line, ``KIND PATTERN REASON``:

  - ``skip PATTERN REASON``: tests whose node id matches PATTERN may skip
    themselves (``pytest.skip``).  An entry whose tests all ran without
    skipping is stale and fails the session (remove it).
  - ``pending PATTERN REASON``: tests that are known not to work yet (e.g. a
    docs example that uses a component not written yet).  They still run,
    as strict xfail: while they fail they are reported as ``xfail`` with the
    reason; the day one passes, the session fails with XPASS(strict) so the
    entry gets removed.

  PATTERN is a node id where ``*`` matches any text (nothing else is special:
  ``[`` and ``]`` of parametrized ids are literal).  REASON is required.
* Any skip or xfail of a test that no entry covers fails the session, with a
  list of them at the end of the output.  pytest.ini adds ``-ra`` so every
  skip and its reason is in the log anyway.

``--area-report FILE`` writes the per-area counts (area = the folder under
tests/, e.g. ``hal``, ``e2e``) as JSON for scripts/test.sh, which prints them
with ctest's count as the last lines of ``make test``.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import pytest

KINDS = ("skip", "pending")


@dataclass
class Entry:
    """One line of the allow-list."""

    kind: str
    pattern: str
    reason: str
    where: str
    regex: re.Pattern[str] = field(repr=False)
    ran: int = 0
    skipped: int = 0

    def matches(self, nodeid: str) -> bool:
        return self.regex.fullmatch(nodeid) is not None


class AllowListError(Exception):
    """The allow-list file is malformed (a line names the problem)."""


def _pattern_regex(pattern: str) -> re.Pattern[str]:
    return re.compile(".*".join(re.escape(part) for part in pattern.split("*")))


def parse_allow_list(path: Path) -> list[Entry]:
    """Entries of the allow-list at path; a missing file is an empty list."""
    if not path.exists():
        return []
    entries: list[Entry] = []
    for n, raw in enumerate(path.read_text().splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        parts = line.split(None, 2)
        where = f"{path}:{n}"
        if len(parts) < 3 or not parts[2].strip():
            raise AllowListError(f"{where}: expected 'KIND PATTERN REASON', got {raw!r}")
        kind, pattern, reason = parts
        if kind not in KINDS:
            raise AllowListError(f"{where}: unknown kind {kind!r} (use {' or '.join(KINDS)})")
        entries.append(Entry(kind, pattern, reason.strip(), where, _pattern_regex(pattern)))
    return entries


def area_of(nodeid: str) -> str:
    """The area of a test: the folder under tests/ (``tests/e2e/hm2/x.py::t`` -> ``e2e``)."""
    parts = nodeid.split("::", 1)[0].split("/")
    if len(parts) >= 3 and parts[0] == "tests":
        return parts[1]
    return parts[0] if len(parts) > 1 else "(top)"


@dataclass
class Counts:
    passed: int = 0
    failed: int = 0
    skipped: int = 0
    xfailed: int = 0
    errors: int = 0


class SkipGuard:
    """State of one session (registered as plugin ``skipguard-state``)."""

    def __init__(self, config: pytest.Config) -> None:
        self.config = config
        self.skips_file = Path(config.getoption("skips_file")).resolve()
        self.entries = parse_allow_list(self.skips_file)
        self.unlisted: list[tuple[str, str]] = []
        self.areas: dict[str, Counts] = {}

    def entry_for(self, nodeid: str, kind: str | None = None) -> Entry | None:
        for e in self.entries:
            if (kind is None or e.kind == kind) and e.matches(nodeid):
                return e
        return None

    # -- collection: requires_build markers, pending entries --------------
    @pytest.hookimpl(tryfirst=True)
    def pytest_collection_modifyitems(self, items: list[pytest.Item]) -> None:
        for item in items:
            e = self.entry_for(item.nodeid, "pending")
            if e is not None:
                item.add_marker(pytest.mark.xfail(reason=f"pending: {e.reason}", strict=True))

    @pytest.hookimpl(tryfirst=True)
    def pytest_runtest_setup(self, item: pytest.Item) -> None:
        missing: list[str] = []
        for mark in item.iter_markers("requires_build"):
            missing += [str(p) for p in mark.args if not Path(p).exists()]
        if missing:
            pytest.fail(
                "required part not built: "
                + ", ".join(missing)
                + " (run `make build`; `make deps` installs the tools it needs)",
                pytrace=False,
            )

    # -- outcomes ----------------------------------------------------------
    def _note_skip(self, nodeid: str, reason: str, xfail: bool) -> None:
        reason = reason.removeprefix("Skipped: ")
        e = self.entry_for(nodeid, "pending" if xfail else "skip")
        if e is None:
            self.unlisted.append((nodeid, ("xfail: " if xfail else "") + reason))
        else:
            e.skipped += 1

    def pytest_collectreport(self, report: pytest.CollectReport) -> None:
        if report.skipped:
            reason = (
                report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
            )
            self._note_skip(report.nodeid, str(reason), xfail=False)
            self.areas.setdefault(area_of(report.nodeid), Counts()).skipped += 1
        elif report.failed:
            self.areas.setdefault(area_of(report.nodeid), Counts()).errors += 1

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        counts = self.areas.setdefault(area_of(report.nodeid), Counts())
        xfail = hasattr(report, "wasxfail")
        if report.skipped:
            if xfail:
                counts.xfailed += 1
                reason = str(report.wasxfail)
            else:
                counts.skipped += 1
                lr = report.longrepr
                reason = str(lr[2]) if isinstance(lr, tuple) else str(lr)
            self._note_skip(report.nodeid, reason, xfail)
            return
        if report.failed:
            if report.when == "call":
                counts.failed += 1
            else:
                counts.errors += 1
            return
        if report.when == "call":
            counts.passed += 1
            e = self.entry_for(report.nodeid, "skip")
            if e is not None:
                e.ran += 1

    # -- verdict -----------------------------------------------------------
    def stale(self) -> list[Entry]:
        return [e for e in self.entries if e.kind == "skip" and e.ran and not e.skipped]

    @pytest.hookimpl(trylast=True)
    def pytest_sessionfinish(self, session: pytest.Session) -> None:
        if (self.unlisted or self.stale()) and session.exitstatus in (
            pytest.ExitCode.OK,
            pytest.ExitCode.NO_TESTS_COLLECTED,
        ):
            session.exitstatus = pytest.ExitCode.TESTS_FAILED
        out = self.config.getoption("area_report")
        if out:
            data = {
                "areas": {a: vars(c) for a, c in sorted(self.areas.items())},
                "unlisted": [list(u) for u in self.unlisted],
                "stale": [f"{e.where}: {e.kind} {e.pattern}" for e in self.stale()],
                "pending": [
                    {"pattern": e.pattern, "reason": e.reason, "xfailed": e.skipped}
                    for e in self.entries
                    if e.kind == "pending"
                ],
            }
            Path(out).write_text(json.dumps(data, indent=1) + "\n")

    def pytest_terminal_summary(self, terminalreporter: pytest.TerminalReporter) -> None:
        tr = terminalreporter
        pending = [e for e in self.entries if e.kind == "pending" and e.skipped]
        if pending:
            tr.section("pending (tests/skips.txt: known not to work yet)")
            for e in pending:
                tr.line(f"{e.skipped:4d} x {e.pattern}: {e.reason}")
        if self.unlisted or self.stale():
            tr.section("skip guard: FAILED", red=True, bold=True)
            for nodeid, reason in self.unlisted:
                tr.line(f"UNLISTED SKIP {nodeid}: {reason}", red=True)
            for e in self.stale():
                tr.line(
                    f"STALE ENTRY {e.where}: '{e.pattern}' ran {e.ran} test(s), none skipped:"
                    " remove the entry",
                    red=True,
                )
            tr.line(
                f"A test that does not run fails: build the missing part, or add an entry"
                f" with its reason to {self.skips_file}."
            )


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("skipguard", "skip allow-list (tests/common/skipguard.py)")
    default = Path(__file__).resolve().parents[1] / "skips.txt"
    group.addoption(
        "--skips-file",
        default=str(default),
        help="skip allow-list (default tests/skips.txt)",
    )
    group.addoption(
        "--area-report", default="", help="write per-area outcome counts as JSON to this file"
    )


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        "requires_build(*paths): the test needs these built files; a missing one fails it",
    )
    try:
        guard = SkipGuard(config)
    except AllowListError as exc:
        raise pytest.UsageError(str(exc)) from None
    config.pluginmanager.register(guard, "skipguard-state")
