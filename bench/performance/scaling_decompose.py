"""The decompositions of scaling_model.py: LAMMPS's processor grid, uniform or balanced cuts, the
discs and ghosts each rank holds, and the messages of a halo exchange."""
import math

import numpy as np

KINDS = ("grid", "grid+balance", "strips", "strips+balance")
SALT_WEIGHT_DECKS = 3.0      # examples/scene/frames.in: fix balance ... weight group 1 salt 3.0


def lammps_grid(P, gridbox):
    """LAMMPS's default 2D processor grid (ProcMap::best_factors with pz = 1): the factors
    px x py = P with the least surface xy/(px py) + xz/px + yz/py of the box it is chosen for."""
    x, y, z = gridbox
    best = None
    for px in range(1, P + 1):
        if P % px:
            continue
        py = P // px
        surf = x * y / (px * py) + x * z / px + y * z / py
        if best is None or surf < best[0]:
            best = (surf, px, py)
    return best[1], best[2]


def cuts(lo, hi, n, coord=None, weight=None):
    """n+1 cut positions: uniform, or at equal quantiles of the weighted coordinates (fix
    balance shift's target)."""
    if coord is None or n == 1:
        return np.linspace(lo, hi, n + 1)
    order = np.argsort(coord)
    c, w = coord[order], weight[order]
    cum = np.cumsum(w)
    q = cum[-1] * np.arange(1, n) / n
    inner = c[np.searchsorted(cum, q)]
    return np.concatenate([[lo], inner, [hi]])


def decompose(scene, P, kind, cutghost, salt_weight=SALT_WEIGHT_DECKS, grid=None):
    """Per rank: owned discs of each type and ghosts; the grid and the thinnest subdomain
    (grid: a measured px, py in place of the kind's)."""
    if grid is not None:
        px, py = grid
    elif kind.startswith("strips"):
        px, py = P, 1
    else:
        px, py = lammps_grid(P, scene.gridbox)
    bal = kind.endswith("balance")
    w = np.where(scene.types == 2, salt_weight, 1.0)
    (xl, xh), (yl, yh) = scene.box[0], scene.box[1]
    xc = cuts(xl, xh, px, scene.x if bal else None, w)
    yc = cuts(yl, yh, py, scene.y if bal else None, w)
    x, y, t = scene.x, scene.y, scene.types
    ranks = []
    for i in range(px):
        a0, a1 = np.searchsorted(x, [xc[i] - cutghost, xc[i + 1] + cutghost])
        xs, ys, ts = x[a0:a1], y[a0:a1], t[a0:a1]
        inx = (xs >= xc[i]) & ((xs < xc[i + 1]) | (i == px - 1))
        for j in range(py):
            iny = (ys >= yc[j]) & ((ys < yc[j + 1]) | (j == py - 1))
            own = inx & iny
            ext = (ys >= yc[j] - cutghost) & (ys < yc[j + 1] + cutghost)
            ranks.append(dict(cover=int(np.sum(own & (ts == 1))), salt=int(np.sum(own & (ts == 2))),
                              wall=int(np.sum(own & (ts == 3))),
                              ghost=int(np.sum(ext & ~own))))
    for r in ranks:
        r["n"] = r["cover"] + r["salt"] + r["wall"]
    return dict(grid=[px, py], ranks=ranks, xcuts=xc.tolist(), ycuts=yc.tolist(),
                min_width=[float(np.min(np.diff(xc))), float(np.min(np.diff(yc)))])


def messages(dec, cutghost):
    """Messages a rank sends per halo exchange (2 per split dimension, more where the ghost
    cutoff spans several subdomains)."""
    m = 0
    for d in range(2):
        if dec["grid"][d] > 1:
            m += 2 * max(1, math.ceil(cutghost / max(dec["min_width"][d], 1e-9)))
    return m


def ghost_summary(dec):
    g = [r["ghost"] for r in dec["ranks"]]
    return dict(ave=float(np.mean(g)), max=int(max(g)), min=int(min(g)), total=int(sum(g)))
