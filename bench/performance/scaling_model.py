#!/usr/bin/env python3
"""Strong-scaling model of the SaltDEM scenes, fitted to the scene benchmark's 1, 2 and 4 rank runs.

    bash bench/performance/run-bench.sh --configs serial,mpi2,mpi2y,mpi4
    PYTHONPATH=python /usr/bin/python3 bench/performance/scaling_model.py out/bench/results.json [--scene-dump DUMP]

Model (docs/performance.md, "Strong scaling: model and projections").  One step on P ranks takes

    T(P) = max over ranks r of [ a_rest N_r + a_pair (N_cover,r + w N_salt,r + N_wall,r)
                                 + b G_r ]
           + passes x msgs(P) x lat + allreduce x ceil(log2 P) x lat

  N_r, N_*,r  discs owned by rank r (all, cover, salt, wall), G_r its ghost discs
  a_pair      pair-force time per step per cover-equivalent disc  <- the 1-rank run's Pair time
  w           a salt disc's pair cost in cover discs               <- the Pair min / max of
              the 2-rank run cut horizontally (mpi2y: processors 1 2 1, one rank holds the salt;
              real cores) with the two ranks' discs of each material; without it (or where a
              split does not separate the materials) the scenes' fix balance weight 3
  a_rest      the rest of the loop per disc (neighbour lists, integration, output, ...)
                                                                   <- the 1-rank run
  b           time per ghost disc (packing, sending, binning, the ghosts' share of the per-atom
              passes)                                              <- the 2-rank run's loop time
              (real cores) less the model's compute of its slowest rank, over that rank's ghosts
  lat         MPI message latency: assumed (--latency, default 1 us: shared memory within a
              node; 1-3 us InfiniBand between nodes, 20-50 us Ethernet), sensitivity printed
  passes      halo exchanges per step: 8 with the full preset's 2 viscous sub-steps, counted in
              the source (forward x/v, reverse forces, the salt's kernel-moment reverse and
              pressure-matrix forward, the density sum's reverse, per sub-step a reverse and
              between sub-steps a forward); allreduce: 1 (the neighbour check) per step
  msgs(P)     messages per rank and pass: 2 per split dimension (x, y of the 2D grid), times
              the subdomains the ghost cutoff spans when a subdomain is thinner than it

Ranks own the discs of their subdomain; ghosts are the discs within the ghost cutoff (the run's
'ghost atom cutoff', the salt's 2h + skin) of the subdomain, outside it - counted on a dump of
the scene.  Decompositions: 'grid' (LAMMPS's default processor grid, chosen - as LAMMPS does -
for the box of the pack file the scene is read from, then cut uniformly over the scene's box),
'grid+balance' (the same grid with cuts that balance x and y separately, as the scenes' fix
balance shift xy with salt weighted 3 does), 'strips' (processors * 1 1, uniform) and
'strips+balance'.  With newton on a pair across a subdomain border is computed once, so the
pair work of the scene is split, not repeated: a ghost costs b, not a pair sum.

The oversubscribed 4-rank run gives counts only (its ghosts, grid, atoms per rank check the
geometry); its timings are not used.  Not modelled: memory bandwidth shared by a node's cores,
turbo frequencies, hyper-threads, OpenMP.

Projections: the full Expt 1 (6250 m section) and the full Expt 2 (12,500 m) as uniform
sections of the densities measured in the benchmark scene (discs per m^2 of cover and of salt,
wall discs at 2 rw spacing along the walls), in their decks' boxes, or the real Expt 1 from a
dump (--scene-dump); steps from examples/scene/params.in's full preset (nsettle + target /
(rate dt)).  Output: a table and OUT.json (default: next to the results file,
scaling-model.json).
"""
import argparse
import json
import math
import pathlib
import sys

import numpy as np

from saltdem_post.dump import read_frame

ROOT = pathlib.Path(__file__).resolve().parents[2]
KINDS = ("grid", "grid+balance", "strips", "strips+balance")
SALT_WEIGHT_DECKS = 3.0      # examples/scene/frames.in: fix balance ... weight group 1 salt 3.0


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results", help="results.json of bench/performance/run-bench.sh with serial, mpi2 "
                   "(real cores), mpi4 (counts) and optionally mpi2y (real cores: fits w)")
    p.add_argument("--dump", default=None, help="dump of the benchmark scene (default: "
                   "bench_settled.dump next to the results file)")
    p.add_argument("--style", default="saltdem", help="style of the runs to fit (saltdem, stock)")
    p.add_argument("--scene-dump", default=None,
                   help="a dump (id type x y ...) of the real full Expt 1 to project instead of "
                   "its uniform section model (e.g. a scene's dump.expt1.50000.txt)")
    p.add_argument("--salt-weight", type=float, default=SALT_WEIGHT_DECKS,
                   help="a salt disc's pair cost in cover discs where the runs cannot fit it "
                   "(default 3, the scenes' fix balance weight; the full Expt 1's profile gives "
                   "4.5: docs/performance.md)")
    p.add_argument("--scene-size", type=float, nargs=3, default=[6250.0, 1000.0, 1750.0],
                   metavar=("WIDTH", "SALT", "COVER"),
                   help="section of the --scene-dump (m; default the full Expt 1's)")
    p.add_argument("--latency", type=float, default=1e-6, help="MPI message latency (s)")
    p.add_argument("--passes", type=int, default=8, help="halo exchanges per step")
    p.add_argument("--allreduce", type=int, default=1, help="global reductions per step")
    p.add_argument("--pmax", type=int, default=48, help="largest rank count")
    p.add_argument("--node", type=int, default=24, help="cores of the node to project")
    p.add_argument("--dt", type=float, default=0.01185,
                   help="time step of the full preset with 2 viscous sub-steps (s)")
    p.add_argument("--rate", type=float, default=0.05, help="drive rate (m/s)")
    p.add_argument("--target", type=float, default=1000.0, help="drive displacement (m)")
    p.add_argument("--nsettle", type=int, default=50000, help="settling steps (full preset)")
    p.add_argument("--one-core-step", type=float, default=None,
                   help="a measured one-core time per step of the real full Expt 1 (s), e.g. "
                   "0.0142 (10.5 ms x 1.35 with 2 sub-steps): also project with a_pair and "
                   "a_rest scaled to it")
    p.add_argument("--two-rank-step", type=float, default=None,
                   help="a measured 2-rank time per step of the real full Expt 1 (s), e.g. 0.0083 "
                   "(2 sub-steps, fix balance, idle machine): with --scene-dump and "
                   "--one-core-step, b refitted to it on the dump's balanced 2-rank split")
    p.add_argument("--pair-fraction", type=float, default=None,
                   help="with --one-core-step: the share of the real one-core step spent in the "
                   "pair styles (e.g. 0.78, the full Expt 1's profile: salt 37 + 20 %%, cover "
                   "21 %%), in place of the benchmark's serial split")
    p.add_argument("--out", default=None, help="output JSON (default scaling-model.json next to "
                   "the results)")
    return p.parse_args(argv)


# ---- scenes --------------------------------------------------------------------------------------

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


# ---- decompositions ------------------------------------------------------------------------------

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


# ---- the model -----------------------------------------------------------------------------------

class Model:
    """b: cost per ghost disc (the 2-rank loss put on the ghosts); k: the other reading of the
    2-rank loss, a constant factor on the compute of every parallel run (b = 0 then)."""

    def __init__(self, a_pair, a_rest, w, b, lat, passes, allreduce, cutghost, k=1.0):
        self.a_pair, self.a_rest, self.w, self.b, self.k = a_pair, a_rest, w, b, k
        self.lat, self.passes, self.allreduce, self.cutghost = lat, passes, allreduce, cutghost

    def copy(self, scale=1.0, **kw):
        m = Model(self.a_pair * scale, self.a_rest * scale, self.w, self.b * scale, self.lat,
                  self.passes, self.allreduce, self.cutghost, self.k)
        m.__dict__.update(kw)
        return m

    def step_overhead(self, dec):
        """The constant-overhead reading: b = 0, compute x k on more than one rank."""
        P = dec["grid"][0] * dec["grid"][1]
        c = max(self.compute(r, 0.0) for r in dec["ranks"])
        return c * (self.k if P > 1 else 1.0) + self.comm(dec)

    def compute(self, r, b=None):
        b = self.b if b is None else b
        return (self.a_rest * r["n"] + self.a_pair * (r["cover"] + self.w * r["salt"] + r["wall"])
                + b * r["ghost"])

    def comm(self, dec):
        P = dec["grid"][0] * dec["grid"][1]
        return (self.passes * messages(dec, self.cutghost) * self.lat
                + (self.allreduce * math.ceil(math.log2(P)) * self.lat if P > 1 else 0.0))

    def step(self, dec, b=None):
        return max(self.compute(r, b) for r in dec["ranks"]) + self.comm(dec)


def run_of(res, config, style):
    for r in res["runs"]:
        if r["config"] == config and r["style"] == style:
            return r
    return None


def ghost_summary(dec):
    g = [r["ghost"] for r in dec["ranks"]]
    return dict(ave=float(np.mean(g)), max=int(max(g)), min=int(min(g)), total=int(sum(g)))


def fit(res, scene, args):
    """The constants from the runs; returns the model and a record of where each came from."""
    s1 = run_of(res, "serial", args.style)
    s2 = run_of(res, "mpi2", args.style)
    s2y = run_of(res, "mpi2y", args.style)
    if s1 is None:
        sys.exit("scaling_model: the results have no serial run of style " + args.style)
    cutghost = s1.get("ghost_cutoff")
    if not cutghost:
        sys.exit("scaling_model: no ghost cutoff in the results (run bench/performance/run-bench.sh of this "
                 "version)")
    rec = dict(cutghost=dict(value=cutghost, source="serial run's log: ghost atom cutoff"))
    n1 = scene.counts()
    T1 = s1["loop_seconds"] / s1["steps"]
    P1 = s1["breakdown"]["Pair"]["avg_seconds"] / s1["steps"]
    # w: the 2-rank Pair time min / max against the two ranks' materials
    w, wsrc = args.salt_weight, "assumed: the scenes' fix balance weight (no 2-rank run)"
    dec2 = None
    if s2 is not None:
        # the run's own grid (its log), uniform cuts (the benchmark has no fix balance)
        dec2 = decompose(scene, 2, "grid", cutghost, grid=(s2.get("grid") or [None])[:2] or None)
    # w from the horizontal cut (mpi2y) where there is one, else from mpi2's split
    for sw in [s for s in (s2y or s2,) if s is not None]:
        decw = decompose(scene, 2, "grid", cutghost, grid=(sw.get("grid") or [None])[:2] or None)
        pr = sw["breakdown"]["Pair"]
        wsrc = "assumed (--salt-weight): no Pair min/max in the 2-rank run"
        if sw.get("oversubscribed"):
            wsrc = "assumed (--salt-weight): the 2-rank run is oversubscribed"
        elif pr.get("min_seconds") and pr.get("max_seconds"):
            R = pr["max_seconds"] / pr["min_seconds"]
            ra, rb = decw["ranks"]
            cands = []
            frac = [r["salt"] / max(r["n"], 1) for r in (ra, rb)]
            if abs(frac[0] - frac[1]) < 0.1:
                # both ranks hold salt and cover alike (vertical cuts through the layers): the
                # Pair times cannot tell a salt disc from a cover disc
                cands = None
                wsrc = (f"assumed (--salt-weight): the {sw['config']} split does not separate "
                        "salt and cover")
            else:
                wsrc = (f"assumed (--salt-weight): the {sw['config']} run's Pair max/min {R:.3f} "
                        "gave no weight in 0.2-50 (timing noise?)")
            for hi, lo in ((ra, rb), (rb, ra)) if cands is not None else ():
                # (c_hi + w s_hi) = R (c_lo + w s_lo), c = cover + wall discs
                den = hi["salt"] - R * lo["salt"]
                if abs(den) > 0.05 * (hi["salt"] + lo["salt"] + 1):
                    wc = (R * (lo["cover"] + lo["wall"]) - hi["cover"] - hi["wall"]) / den
                    if 0.2 < wc < 50:
                        cands.append(wc)
            if cands:
                w = min(cands, key=lambda v: abs(math.log(v / args.salt_weight)))
                wsrc = (f"fitted: the {sw['config']} run's Pair max/min {R:.3f} with the ranks' "
                        "salt and cover counts from the dump")
                break
    rec["w"] = dict(value=w, source=wsrc)
    a_pair = P1 / (n1["cover"] + w * n1["salt"] + n1["wall"])
    a_rest = (T1 - P1) / sum(n1.values())
    rec["a_pair"] = dict(value=a_pair, unit="s per step per cover-equivalent disc",
                         source="serial run's Pair time")
    rec["a_rest"] = dict(value=a_rest, unit="s per step per disc",
                         source="serial run's loop time less its Pair time")
    m = Model(a_pair, a_rest, w, 0.0, args.latency, args.passes, args.allreduce, cutghost)
    # b: the 2-rank loop time over the model's slowest rank, per ghost of that rank
    b, bsrc = 0.0, "set to 0 (no 2-rank run on real cores)"
    if s2 is not None and not s2.get("oversubscribed"):
        T2 = s2["loop_seconds"] / s2["steps"]
        slow = max(dec2["ranks"], key=lambda r: m.compute(r))
        rest = T2 - m.compute(slow) - m.comm(dec2)
        if slow["ghost"] > 0 and rest > 0:
            b, bsrc = rest / slow["ghost"], "fitted: the 2-rank run's loop time"
        else:
            bsrc = (f"set to 0: the 2-rank loop time is {rest / T2:+.1%} off the ghost-free "
                    "compute of its slowest rank")
        m.k = (T2 - m.comm(dec2)) / m.compute(slow, 0.0)
    m.b = b
    rec["k"] = dict(value=m.k, source="the 2-rank run's loop time over the model's ghost-free "
                    "step (the other reading of the same loss: a constant overhead)")
    rec["b"] = dict(value=b, unit="s per step per ghost disc", source=bsrc)
    rec["latency"] = dict(value=args.latency, source="assumed (--latency)")
    rec["passes"] = dict(value=args.passes, source="counted in the source (--passes)")
    rec["serial_step"] = T1
    low = [f"{r['config']} {r.get('cpu_percent', 0):.0f} %" for r in (s1, s2) if r is not None
           and r.get("cpu_percent", 100.0) < 90.0 * r["ranks"] * r["threads"] / max(r["ranks"], 1)]
    rec["warning"] = ("the fitted runs did not get a full core each (CPU use " + ", ".join(low)
                      + "): their timings are not speed, the constants not either") if low else ""
    return m, rec, dec2


def validate(res, scene, m, args):
    """Measured against modelled: grids, ghosts, atoms per rank, the 2-rank time."""
    out = {}
    for config, P in (("mpi2", 2), ("mpi2y", 2), ("mpi4", 4)):
        r = run_of(res, config, args.style)
        if r is None:
            continue
        # mpi2y: processors 1 2 1, the model's grid is the measured one by construction
        dec = decompose(scene, P, "grid", m.cutghost,
                        grid=(r.get("grid") or [1, 2])[:2] if config == "mpi2y" else None)
        nl = [x["n"] for x in dec["ranks"]]
        v = dict(grid_measured=(r.get("grid") or [None, None])[:2], grid_model=dec["grid"],
                 nghost_measured=r.get("counts", {}).get("Nghost"), nghost_model=ghost_summary(dec),
                 nlocal_measured=r.get("counts", {}).get("Nlocal"),
                 nlocal_model=dict(ave=float(np.mean(nl)), max=max(nl), min=min(nl)),
                 oversubscribed=bool(r.get("oversubscribed")))
        if not r.get("oversubscribed"):
            T = r["loop_seconds"] / r["steps"]
            pr = r["breakdown"]["Pair"]
            # without the run's own timings (b = 0, w the decks' 3): a prediction, not a fit
            m0 = Model(m.a_pair, m.a_rest, args.salt_weight, 0.0, m.lat, m.passes,
                       m.allreduce, m.cutghost)
            s1 = run_of(res, "serial", args.style)
            n1 = scene.counts()
            m0.a_pair = s1["breakdown"]["Pair"]["avg_seconds"] / s1["steps"] / (
                n1["cover"] + args.salt_weight * n1["salt"] + n1["wall"])
            decm = decompose(scene, P, "grid", m.cutghost, grid=v["grid_measured"])
            pw = [m.a_pair * (x["cover"] + m.w * x["salt"] + x["wall"]) for x in decm["ranks"]]
            v.update(step_measured=T, step_fitted=m.step(decm),
                     step_fitted_overhead=m.step_overhead(decm),
                     step_predicted_from_serial_only=m0.step(decm),
                     pair_imbalance_measured=pr.get("imbalance"),
                     pair_imbalance_model=max(pw) / np.mean(pw) if np.mean(pw) > 0 else None)
        out[config] = v
    return out


def project(scene, m, args, steps, scale=1.0):
    """Speed-up, efficiency and step time for P = 1..pmax in each decomposition."""
    ms = m.copy(scale)
    base = ms.step(decompose(scene, 1, "grid", m.cutghost))
    rows = {}
    for kind in KINDS:
        rows[kind] = []
        for P in range(1, args.pmax + 1):
            dec = decompose(scene, P, kind, m.cutghost)
            T = ms.step(dec)
            comp = [ms.compute(r) for r in dec["ranks"]]
            To = ms.step_overhead(dec)
            rows[kind].append(dict(P=P, grid=dec["grid"], step_s=T, speedup=base / T,
                                   efficiency=base / T / P, step_overhead_s=To,
                                   speedup_overhead=base / To, efficiency_overhead=base / To / P,
                                   imbalance=max(comp) / np.mean(comp),
                                   ghost=ghost_summary(dec), msgs=messages(dec, m.cutghost),
                                   comm_s=ms.comm(dec)))
    node = {k: rows[k][args.node - 1] for k in KINDS} if args.node <= args.pmax else {}
    return dict(scene=scene.name, discs=int(len(scene.x)), counts=scene.counts(), steps=steps,
                serial_step_s=base, serial_hours=base * steps / 3600.0,
                node={k: dict(P=args.node, speedup=v["speedup"], efficiency=v["efficiency"],
                              hours=v["step_s"] * steps / 3600.0,
                              speedup_overhead=v["speedup_overhead"],
                              efficiency_overhead=v["efficiency_overhead"],
                              hours_overhead=v["step_overhead_s"] * steps / 3600.0)
                      for k, v in node.items()},
                table=rows)


def main(argv=None):
    args = parse_args(argv)
    rpath = pathlib.Path(args.results)
    res = json.loads(rpath.read_text())
    dump = pathlib.Path(args.dump) if args.dump else rpath.parent / "bench_settled.dump"
    if not dump.exists():
        sys.exit(f"scaling_model: no scene dump {dump} (bench/performance/run-bench.sh writes "
                 "bench_settled.dump in its output directory)")
    sc = res["scene"]
    width = sc["width"]
    salt = sc.get("salt") or 1000.0
    cover = sc.get("cover") or 1750.0
    bench = dump_scene(dump, "benchmark scene", width, salt + cover)
    m, rec, dec2 = fit(res, bench, args)
    valid = validate(res, bench, m, args)
    steps = args.nsettle + args.target / (args.rate * args.dt)
    dens = densities(bench, salt, cover, width)
    real = None
    if args.scene_dump:
        W, S, C = args.scene_size
        real = dump_scene(args.scene_dump, "full Expt 1 (dump)", W, S + C)
        # the real scene's densities for the uniform sections (the benchmark's tiled pack, and
        # a small one most, is a little looser)
        dens = densities(real, S, C, W)
    scenes = expt_scenes(dens)
    if real is not None:
        scenes["expt1-dump"] = real
    proj = {k: project(s, m, args, steps) for k, s in scenes.items()}
    if "expt1-dump" in scenes:
        # what LAMMPS reports for this scene on 2 ranks before any fix balance (uniform cut)
        d = decompose(scenes["expt1-dump"], 2, "grid", m.cutghost)
        proj["expt1-dump"]["check_2ranks_uniform"] = dict(
            grid=d["grid"], nlocal=[r["n"] for r in d["ranks"]], nghost=[r["ghost"] for r in d["ranks"]],
            cutghost=m.cutghost)
    calibrated = {}
    if args.one_core_step:
        # the real scene's one-core step against the model's: scale the per-disc constants
        key = "expt1-dump" if "expt1-dump" in proj else "expt1"
        scale = args.one_core_step / proj[key]["serial_step_s"]
        mc = m.copy()
        note = f"a_pair, a_rest, b x {scale:.4g} (the real one-core step over the model's)"
        if args.pair_fraction is not None:
            # the real step's own split between the pairs and the rest (its profile)
            c = scenes[key].counts()
            T = args.one_core_step
            mc.w = args.salt_weight
            mc.a_pair = args.pair_fraction * T / (c["cover"] + mc.w * c["salt"] + c["wall"]) / scale
            mc.a_rest = (1 - args.pair_fraction) * T / sum(c.values()) / scale
            note += (f"; pair share {args.pair_fraction:g} of it (--pair-fraction), salt weight "
                     f"{mc.w:g} (--salt-weight)")
        if args.two_rank_step and key == "expt1-dump":
            # b from the real 2-rank step on the dump's balanced split (the scenes' fix balance)
            dec = decompose(scenes[key], 2, "grid+balance", m.cutghost)
            ms = mc.copy(scale, b=0.0)
            slow = max(dec["ranks"], key=lambda r: ms.compute(r))
            rest = args.two_rank_step - ms.step(dec)
            mc.b = max(rest, 0.0) / slow["ghost"] / scale
            mc.k = (args.two_rank_step - ms.comm(dec)) / ms.compute(slow, 0.0)
            note += (f"; b {mc.b * scale:.4g} s per ghost from the real 2-rank step "
                     f"{args.two_rank_step * 1e3:.3g} ms (model without ghost cost "
                     f"{ms.step(dec) * 1e3:.3g} ms, {slow['ghost']} ghosts on the slower rank), "
                     f"or a constant overhead k {mc.k:.3f}")
        calibrated = {k: project(sc_, mc, args, steps, scale) for k, sc_ in scenes.items()}
        calibrated["scale"] = dict(scale=scale, note=note)
    lat = {}
    mfin, sfin = m, 1.0
    if calibrated:
        mfin, sfin = mc, calibrated["scale"]["scale"]
    for L in (0.3e-6, 1e-6, 3e-6, 10e-6, 50e-6):
        ml = mfin.copy(sfin, lat=L)
        s = scenes["expt1"]
        base = ml.step(decompose(s, 1, "grid", m.cutghost))
        lat[f"{L:g}"] = {}
        for k in ("grid+balance", "strips+balance"):
            d = decompose(s, args.node, k, m.cutghost)
            lat[f"{L:g}"][k] = [base / ml.step(d) / args.node,
                                base / ml.step_overhead(d) / args.node]
    out = dict(results=str(rpath), dump=str(dump), measured_machine=res.get("machine"),
               model=rec, bench_scene=dict(counts=bench.counts()), densities=dict(
                   dens, source="the --scene-dump" if real is not None else "the benchmark scene"),
               validation=valid, steps=dict(full_preset=steps, dt=args.dt, rate=args.rate,
                                            target=args.target, nsettle=args.nsettle),
               projections=proj, calibrated=calibrated,
               latency_sensitivity=dict(scene="expt1", P=args.node,
                                        model="calibrated" if calibrated else "fitted",
                                        efficiency_ghost_and_overhead=lat))
    opath = pathlib.Path(args.out) if args.out else rpath.parent / "scaling-model.json"
    opath.write_text(json.dumps(out, indent=1) + "\n")
    print(report(out, args), end="")
    print(f"scaling_model: written {opath}")
    return 0


def report(o, args):
    L = []
    md = o["model"]
    L.append("SaltDEM strong-scaling model (bench/performance/scaling_model.py)")
    L.append(f"from {o['results']}  scene dump {o['dump']}")
    for k in ("a_pair", "a_rest", "w", "b", "k", "cutghost", "latency", "passes"):
        v = md[k]
        L.append(f"  {k:<9} {v['value']:.4g} {v.get('unit', '')}  <- {v['source']}")
    L.append(f"  1-rank step of the benchmark scene: {md['serial_step'] * 1e3:.3f} ms")
    if md.get("warning"):
        L.append("  WARNING: " + md["warning"])
    L.append("validation (grid and counts from the runs' logs; the 4-rank run counts only):")
    for c, v in o["validation"].items():
        g = v["nghost_measured"] or {}
        gm = v["nghost_model"]
        nl = v["nlocal_measured"] or {}
        L.append(f"  {c}: grid {v['grid_measured']} model {v['grid_model']}; Nghost ave/max/min "
                 f"{g.get('ave')}/{g.get('max')}/{g.get('min')} model "
                 f"{gm['ave']:.0f}/{gm['max']}/{gm['min']}; Nlocal max/min "
                 f"{nl.get('max')}/{nl.get('min')} model {v['nlocal_model']['max']}/{v['nlocal_model']['min']}"
                 + ("  (oversubscribed: counts only)" if v["oversubscribed"] else ""))
        if "step_measured" in v:
            L.append(f"     step measured {v['step_measured'] * 1e3:.3f} ms, model "
                     f"{v['step_fitted'] * 1e3:.3f} ms (ghost cost b) / "
                     f"{v['step_fitted_overhead'] * 1e3:.3f} ms (overhead k), predicted from the 1-rank run and the "
                     f"geometry alone {v['step_predicted_from_serial_only'] * 1e3:.3f} ms; Pair "
                     f"max/avg measured {v['pair_imbalance_measured'] or float('nan'):.3f} model "
                     f"{v['pair_imbalance_model'] or float('nan'):.3f}")
    st = o["steps"]
    L.append(f"steps of a full run: {st['nsettle']} + {st['target']:g} m / ({st['rate']:g} m/s x "
             f"{st['dt']:g} s) = {st['full_preset']:.4g}")
    for tag, proj in (("model", o["projections"]), ("calibrated to the real one-core step",
                                                    o.get("calibrated") or {})):
        for k, p in proj.items():
            if k == "scale":
                L.append("  (" + p["note"] + ")")
                continue
            L.append(f"{p['scene']} [{tag}]: {p['discs']} discs, 1 core {p['serial_step_s'] * 1e3:.2f} "
                     f"ms/step, {p['serial_hours']:.1f} h")
            if "check_2ranks_uniform" in p and tag == "model":
                c = p["check_2ranks_uniform"]
                L.append(f"  2 ranks, grid {c['grid']} cut uniformly (no fix balance): Nlocal "
                         f"{c['nlocal']}, Nghost {c['nghost']} (compare the scene's own 2-rank log)")
            for kind, n in p["node"].items():
                L.append(f"  {args.node} ranks, {kind:<15} speed-up {n['speedup']:5.1f}, efficiency "
                         f"{n['efficiency']:.2f}, {n['hours']:.2f} h  | constant overhead: "
                         f"{n['speedup_overhead']:5.1f}, {n['efficiency_overhead']:.2f}, "
                         f"{n['hours_overhead']:.2f} h")
            if tag == "model":
                L.append("  P: " + " ".join(f"{r['P']:>5}" for r in p["table"]["strips+balance"]
                                            if r["P"] in (1, 2, 4, 8, 12, 16, 24, 32, 48)))
                for kind in KINDS:
                    L.append(f"  {kind:<15} eff " + " ".join(
                        f"{r['efficiency']:5.2f}" for r in p["table"][kind]
                        if r["P"] in (1, 2, 4, 8, 12, 16, 24, 32, 48)) + "  ghosts/rank max "
                        + " ".join(str(r["ghost"]["max"]) for r in p["table"][kind]
                                   if r["P"] in (2, 24, 48)) + " at 2/24/48")
    ls = o["latency_sensitivity"]
    L.append(f"latency sensitivity (full Expt 1 uniform section, {args.node} ranks, {ls['model']} "
             "model; efficiency with the ghost cost / with the constant overhead):")
    for l, v in ls["efficiency_ghost_and_overhead"].items():
        L.append(f"  {float(l) * 1e6:5.1f} us: " + ", ".join(f"{k} {e[0]:.2f} / {e[1]:.2f}"
                                                          for k, e in v.items()))
    return "\n".join(L) + "\n"


if __name__ == "__main__":
    sys.exit(main())
