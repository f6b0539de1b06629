"""Progress display for long jobs: frames processed, bytes read, ETA.

Progress is measured in bytes of input read (compressed bytes for ``.gz``),
which is known up front for any number of files without scanning them.
"""

from __future__ import annotations

import sys
import time
from typing import Optional, TextIO


def _hms(seconds: float) -> str:
    seconds = int(round(seconds))
    h, rem = divmod(seconds, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class Progress:
    """Prints ``label: N frames (M parsed) 42% ETA 0:13`` to a stream.

    On a terminal the line is redrawn in place; elsewhere (log files) a new
    line is written at most every ``interval`` seconds, so logs stay short.
    """

    def __init__(self, label: str = "reading", stream: Optional[TextIO] = None,
                 enabled: bool = True, interval: Optional[float] = None):
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.interval = interval if interval is not None else (0.2 if self.tty else 10.0)
        self.total = 0
        self.frames = 0
        self.parsed = 0
        self._t0 = self._last = time.monotonic()
        self._shown = False

    def start(self, total_bytes: int) -> None:
        self.total = max(int(total_bytes), 1)
        self.frames = self.parsed = 0
        self._t0 = self._last = time.monotonic()

    def fraction(self, done: int) -> float:
        return min(max(done / self.total, 0.0), 1.0) if self.total else 0.0

    def eta(self, done: int) -> Optional[float]:
        f, elapsed = self.fraction(done), time.monotonic() - self._t0
        return elapsed * (1.0 - f) / f if f > 0 else None

    def update(self, done_bytes: int, parsed: bool = True, label: str = "") -> None:
        self.frames += 1
        self.parsed += int(parsed)
        now = time.monotonic()
        if not self.enabled or now - self._last < self.interval:
            return
        self._last = now
        self._emit(self._line(done_bytes, label))

    def _line(self, done: int, label: str) -> str:
        eta = self.eta(done)
        text = (f"{self.label}: {self.frames} frames ({self.parsed} parsed)"
                f" {100 * self.fraction(done):3.0f}% ETA {_hms(eta) if eta is not None else '?'}")
        return f"{text} [{label}]" if label else text

    def _emit(self, line: str) -> None:
        if self.tty:
            self.stream.write("\r" + line.ljust(79))
        else:
            self.stream.write(line + "\n")
        self.stream.flush()
        self._shown = True

    def finish(self) -> None:
        if not self.enabled:
            return
        elapsed = time.monotonic() - self._t0
        line = f"{self.label}: {self.frames} frames ({self.parsed} parsed) in {_hms(elapsed)}"
        if self.tty:
            self.stream.write("\r" + line.ljust(79) + "\n")
        elif self._shown or elapsed > self.interval:
            self.stream.write(line + "\n")
        self.stream.flush()
