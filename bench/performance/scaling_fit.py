"""The model of scaling_model.py: the step time of a decomposition, its constants fitted to the
benchmark runs, the runs checked against it, and the projections for P = 1..pmax."""
import math
import sys

import numpy as np

from scaling_decompose import KINDS, decompose, ghost_summary, messages


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
