# SPDX-License-Identifier: GPL-2.0-or-later
"""A long-running viewer's place in the HAL session.

halmeter and the web server register a HAL user component named
``PROGRAM-PID`` (LinuxCNC's halmeter calls itself ``halmeter-PID``) for as
long as they run: it is listed by ``show comp``, and ending the session
(``halrun -U``, ``unload all``) ends the viewer with SIGTERM as it ends
every user component, instead of leaving it watching a session that is gone.
"""

from __future__ import annotations

import os
from types import TracebackType


class SessionComponent:
    def __init__(self, program: str) -> None:
        self.name = f"{program}-{os.getpid()}"
        self.comp: object | None = None

    def __enter__(self) -> "SessionComponent":
        import hal

        self.comp = hal.component(self.name)
        self.comp.ready()  # type: ignore[attr-defined]
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        if self.comp is not None:
            self.comp.exit()  # type: ignore[attr-defined]
            self.comp = None
