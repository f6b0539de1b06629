"""Which frames of a dump series to read: indices, slices and timesteps."""

from __future__ import annotations

from typing import List, Optional, Sequence


class FrameSelection:
    """Which frames to read: indices (negative counts from the end), slices
    written ``start:stop[:step]``, and/or timesteps.  Empty selects all."""

    def __init__(self, frames: Optional[Sequence] = None, timesteps: Optional[Sequence[int]] = None):
        self.items = []
        for tok in frames or []:
            tok = str(tok).strip()
            if tok in ("all", ":"):
                self.items.append(slice(None))
            elif ":" in tok:
                parts = [int(p) if p.strip() else None for p in tok.split(":")]
                self.items.append(slice(*parts))
            else:
                self.items.append(int(tok))
        self.timesteps = set(int(t) for t in timesteps or [])

    @property
    def everything(self) -> bool:
        return not self.items and not self.timesteps

    @property
    def needs_count(self) -> bool:
        """Whether resolving the selection needs the total number of frames."""
        for it in self.items:
            if isinstance(it, int) and it < 0:
                return True
            if isinstance(it, slice) and any(v is not None and v < 0 for v in (it.start, it.stop, it.step)):
                return True
        return False

    def resolve(self, n_frames: int) -> List[int]:
        """Sorted frame indices selected out of ``n_frames`` (timesteps aside)."""
        out = set()
        for it in self.items:
            if isinstance(it, slice):
                out.update(range(n_frames)[it])
            elif -n_frames <= it < n_frames:
                out.add(it % n_frames)
            else:
                raise IndexError(f"frame index {it} out of range ({n_frames} frames)")
        return sorted(out)

    def predicate(self, n_frames: Optional[int]):
        """Return ``(wanted(index, timestep) -> bool, last index needed or None)``.

        ``n_frames`` may be None unless :attr:`needs_count`; then slices are
        tested lazily (they have no negative parts in that case).
        """
        if self.everything:
            return (lambda i, t: True), None
        if n_frames is not None:
            fixed, slices = set(self.resolve(n_frames)), []
        elif self.needs_count:
            raise ValueError("negative frame indices need the number of frames")
        else:
            fixed = {i for i in self.items if isinstance(i, int)}
            slices = [s for s in self.items if isinstance(s, slice)]
        steps = self.timesteps

        def wanted(i, t):
            return i in fixed or t in steps or any(_in_slice(i, s) for s in slices)

        open_ended = steps or any(s.stop is None for s in slices)
        last = None if open_ended else max(list(fixed) + [s.stop - 1 for s in slices], default=None)
        return wanted, last


def _in_slice(i: int, s: slice) -> bool:
    start, step = s.start or 0, s.step or 1
    return i >= start and (s.stop is None or i < s.stop) and (i - start) % step == 0
