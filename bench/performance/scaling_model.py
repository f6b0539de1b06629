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

The code: this file (the command line, the report), scaling_scenes.py (the scenes),
scaling_decompose.py (the decompositions), scaling_fit.py (the model, its fit, the projections).
"""
import argparse
import json
import pathlib
import sys

# the scaling_*.py modules next to this script
from scaling_decompose import KINDS, SALT_WEIGHT_DECKS, decompose
from scaling_fit import fit, project, validate
from scaling_scenes import densities, dump_scene, expt_scenes

ROOT = pathlib.Path(__file__).resolve().parents[2]


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
