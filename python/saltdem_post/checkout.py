"""The SaltDEM checkout and its LAMMPS: where the decks, tools and the built
``lmp`` are, and packs made with its packing tool.  Shared by the
calibration, the benchmarks in bench/ and the tests."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Optional


def is_checkout(path: Path) -> bool:
    return (path / "examples" / "calibration" / "biaxial.in").is_file() and (path / "tools" / "pack.in").is_file()


def find_repo() -> Optional[Path]:
    """The SaltDEM checkout whose decks, packing tool, potentials and build/lmp
    the tools use: $SALTDEM_ROOT if set, else the checkout this package sits
    in (python/saltdem_post/ of a checkout: the wrappers python/saltdem-*),
    else (an installed package) the current directory or the nearest
    directory above it that is a checkout.  None if there is none."""
    env = os.environ.get("SALTDEM_ROOT")
    if env:
        return Path(env).resolve()
    here = Path(__file__).resolve().parents[2]
    if is_checkout(here):
        return here
    cwd = Path.cwd().resolve()
    return next((d for d in (cwd, *cwd.parents) if is_checkout(d)), None)


def repo() -> Path:
    """find_repo(), or where a checkout would hold this package (for the
    error message that there is none)."""
    found = find_repo()
    return found if found is not None else Path(__file__).resolve().parents[2]


def lmp_path(root: Optional[Path] = None) -> str:
    """The LAMMPS executable: $SALTDEM_LMP, else build/lmp of the checkout
    (``root``, default repo())."""
    return os.environ.get("SALTDEM_LMP", str(Path(root or repo()) / "build" / "lmp"))


def make_pack(lmp: str, work: Path, W, H, rmin, rmax, seed=7, dist="uniform", root: Optional[Path] = None,
              D=None) -> Path:
    """A settled pack of tools/pack.in on y = 0, made once and kept in work; D: a 3D sphere pack
    that deep along z (settled with the 2D stiffness times rmin + rmax, as the 3D scenes)."""
    work.mkdir(parents=True, exist_ok=True)
    out = work / (f"pack_{W}x{H}_{rmin}_{rmax}_{dist}_{seed}.data" if D is None
                  else f"pack_{W}x{H}x{D}_{rmin}_{rmax}_{dist}_{seed}.data")
    if not out.exists():
        tool = Path(root or repo()) / "tools" / "pack.in"
        kn = 5e9 if D is None else 5e9 * (rmin + rmax)
        dim = [] if D is None else ["-var", "dim", "3", "-var", "D", str(D)]
        subprocess.run([lmp, "-in", str(tool), "-log", "none", "-screen",
                        "none", "-nocite", "-var", "W", str(W), "-var", "H", str(H), "-var", "rmin",
                        str(rmin), "-var", "rmax", str(rmax), "-var", "dist", dist, "-var",
                        "seed", str(seed), "-var", "kn", str(kn), "-var", "out", out.name + ".tmp", *dim],
                       cwd=work, check=True, stdout=subprocess.DEVNULL)
        (work / (out.name + ".tmp")).rename(out)
    return out
