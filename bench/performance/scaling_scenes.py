"""The scenes of scaling_model.py: the discs of a scene dump (the benchmark's, the real Expt 1's)
and the full Expt 1 and 2 as uniform sections at the measured densities."""
import math

import numpy as np

from saltdem_post.dump import read_frame


class Scene:
    """Discs (type 1 cover, 2 salt, 3 wall; x, y), the scene's box and the box LAMMPS chose its
    processor grid for (the pack file's)."""

    def __init__(self, name, types, x, y, box, gridbox):
        order = np.argsort(x, kind="stable")
        self.name, self.types, self.x, self.y = name, types[order], x[order], y[order]
        self.box, self.gridbox = box, gridbox

    def counts(self):
        return {k: int(np.sum(self.types == t)) for k, t in (("cover", 1), ("salt", 2), ("wall", 3))}


def dump_scene(path, name, width=None, height=None):
    f = read_frame([str(path)], -1)
    box = [[float(f.box.lo[d]), float(f.box.hi[d])] for d in range(3)]
    t, x, y = f["type"].astype(int), f.x, f.y
    if width is None:       # the section: the extent of the cover and salt discs
        pack = t < 3
        width = float(x[pack].max() - x[pack].min())
        height = float(y[pack].max() - y[pack].min())
    gridbox = (width, height, box[2][1] - box[2][0])
    return Scene(name, t, x, y, box, gridbox)


def lattice(x0, x1, y0, y1, n):
    """Points at areal density n on a square lattice filling the rectangle."""
    s = 1.0 / math.sqrt(n)
    xs = np.arange(x0 + s / 2, x1, s)
    ys = np.arange(y0 + s / 2, y1, s)
    X, Y = np.meshgrid(xs, ys)
    return X.ravel(), Y.ravel()


def line(x0, y0, x1, y1, spacing):
    m = max(1, int(round(math.hypot(x1 - x0, y1 - y0) / spacing)))
    f = (np.arange(m) + 0.5) / m
    return x0 + f * (x1 - x0), y0 + f * (y1 - y0)


def section_scene(name, width, salt, cover, box, walls, dens, zprd):
    """A uniform section: cover and salt at the measured densities, wall discs along the given
    segments at 2 rw spacing."""
    parts = [(2, *lattice(0, width, 0, salt, dens["salt"])),
             (1, *lattice(0, width, salt, salt + cover, dens["cover"]))]
    for seg in walls:
        parts.append((3, *line(*seg, dens["wall_spacing"])))
    t = np.concatenate([np.full(len(p[1]), p[0]) for p in parts])
    x = np.concatenate([p[1] for p in parts])
    y = np.concatenate([p[2] for p in parts])
    return Scene(name, t, x, y, box, (width, salt + cover, zprd))


def densities(scene, salt, cover, width):
    """Discs per m^2 of salt and cover and the wall discs' spacing, from a scene dump."""
    c = scene.counts()
    rw = 6.25
    return dict(salt=c["salt"] / (width * salt), cover=c["cover"] / (width * cover),
                wall_spacing=2 * rw)


def expt_scenes(dens, rmax=15.625, salt=1000.0, cover=1750.0, target=1000.0, zprd=2000.0):
    """The full Expt 1 and Expt 2 as uniform sections in their decks' boxes (examples/expt1.in,
    examples/expt2.in: box, end walls, base and fault faces)."""
    H = salt + cover
    out = {}
    W = 6250.0                                  # Expt 1, 30 degree fault at W/2
    sd, cd = math.sin(math.radians(30)), math.cos(math.radians(30))
    box = [[-3 * rmax, W + 3 * rmax + target], [-target - 6 * rmax, H + 2 * salt], [-1e3, 1e3]]
    walls = [(0, 0, W, 0), (0, 0, 0, H + salt), (W, 0, W, H + salt),
             (W / 2, 0, W / 2 + target * cd, -target * sd)]
    out["expt1"] = section_scene("full Expt 1 (uniform section, 6250 m)", W, salt, cover, box,
                                 walls, dens, zprd)
    W = 12500.0                                 # Expt 2, 60 degree faults, 2500 m keystone
    sd, cd = math.sin(math.radians(60)), math.cos(math.radians(60))
    x1, x2 = (W - 2500) / 2, (W + 2500) / 2
    box = [[-3 * rmax, W + 3 * rmax + 2 * target * cd], [-target - 6 * rmax, 1.5 * H], [-1e3, 1e3]]
    walls = [(0, 0, W, 0), (0, 0, 0, H + salt), (W, 0, W, H + salt),
             (x1, 0, x1 + target * cd, -target * sd), (x2, 0, x2 - target * cd, -target * sd)]
    out["expt2"] = section_scene("full Expt 2 (uniform section, 12,500 m)", W, salt, cover, box,
                                 walls, dens, zprd)
    return out
