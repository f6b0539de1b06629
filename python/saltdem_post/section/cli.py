"""The saltdem-section command."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .deck import deck
from .describe import parse
from .model import SectionError


def build(path: Path) -> str:
    s = parse(Path(path).read_text(), str(path))
    return deck(s)


USAGE = """Write the LAMMPS deck of a section description (docs/sections.md).

  saltdem-section SECTION.toml [-o DECK.in]   write the deck (default: NAME.in here)
  saltdem-section SECTION.toml --check        check the description, write nothing

Then: lmp -in DECK.in -var root <repository> -var preset quick
"""


def main(argv=None):
    ap = argparse.ArgumentParser(prog="saltdem-section", description=USAGE,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("section", type=Path, help="the section description (TOML)")
    ap.add_argument("-o", "--output", type=Path, help="the deck to write (default: NAME.in)")
    ap.add_argument("--check", action="store_true", help="check the description only")
    ap.add_argument("--faults", action="store_true",
                    help="print where the faults cut the basement top (x, m), for saltdem-post --fault-x")
    ap.add_argument("--types", action="store_true",
                    help="print the type map of its frames, for saltdem-post --types")
    a = ap.parse_args(argv)
    try:
        text = a.section.read_text()
    except OSError as e:
        print(f"saltdem-section: cannot read {a.section}: {e.strerror}", file=sys.stderr)
        return 2
    try:
        s = parse(text, str(a.section))
        out = deck(s)
    except SectionError as e:
        print(f"saltdem-section: {e}", file=sys.stderr)
        return 1
    if a.faults:
        print(" ".join(f"{f.x:g}" for f in s.faults))
        return 0
    if a.types:
        print("cover=" + ",".join(str(t) for t in sorted({1} | {u.type for u in s.units})) + ";salt=2;wall=3")
        return 0
    if a.check:
        print(f"saltdem-section: {a.section}: section '{s.name}' is fine "
              f"({len(s.faults)} fault(s), {len(s.blocks)} block(s))")
        return 0
    dest = a.output or Path(f"{s.name}.in")
    dest.write_text(out)
    print(f"saltdem-section: wrote {dest}")
    return 0


