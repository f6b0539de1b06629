"""The calibration report: ``report.md`` (tables) and PNG plots, written from
the ``results.json`` of ``saltdem-calibrate`` (see ``saltdem_post.calibration.cli``)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import List, Optional

import matplotlib

matplotlib.use("Agg")                         # files only, never a window
import matplotlib.pyplot as plt               # noqa: E402
import numpy as np                            # noqa: E402

from .fit import sigma1_from_mc          # noqa: E402

MPA = 1e6
DPI = 90


def _f(v, d=4):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:.{d}g}"


def _table(head: List[str], rows: List[list]) -> List[str]:
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return out + [""]


def _save(fig, path: Path) -> str:
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path.name


# ------------------------------------------------------------------- biaxial

def plot_biaxial_curves(r: dict, path: Path) -> str:
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6))
    confs = sorted({t["sigma3_target"] for t in r["tests"]})
    cmap = plt.get_cmap("viridis")
    seeds = sorted({t["seed"] for t in r["tests"]})
    styles = ["-", "--", ":", "-."]
    for t in r["tests"]:
        c = cmap(confs.index(t["sigma3_target"]) / max(1, len(confs) - 1) * 0.9)
        ls = styles[seeds.index(t["seed"]) % len(styles)]
        cu = t["curve"]
        ea = 100 * np.asarray(cu["axial"])
        q = (np.asarray(cu["sigma1"]) - np.asarray(cu["sigma3"])) / MPA
        lab = f"{t['sigma3_target'] / MPA:g} MPa" if seeds.index(t["seed"]) == 0 else None
        a1.plot(ea, q, ls, color=c, lw=0.9, label=lab)
        a1.plot(100 * t["peak"]["axial"], t["peak"]["q"] / MPA, "o", color=c, ms=4)
        a2.plot(ea, -100 * np.asarray(cu["volumetric"]), ls, color=c, lw=0.9)
    a1.set_xlabel("axial strain (%)")
    a1.set_ylabel(r"$\sigma_1-\sigma_3$ (MPa)")
    a1.legend(title=r"$\sigma_3$", fontsize=8)
    a1.set_title("deviatoric stress (dots: peaks)", fontsize=10)
    a2.set_xlabel("axial strain (%)")
    a2.set_ylabel("volumetric strain (%, dilation +)")
    a2.set_title("dilatancy", fontsize=10)
    a2.axhline(0, color="0.6", lw=0.6)
    return _save(fig, path)


def plot_mohr(r: dict, path: Path, targets: Optional[dict]) -> str:
    fit = r["fit"]
    s3 = np.array([t["peak"]["sigma3"] for t in r["tests"]])
    s1 = np.array([t["peak"]["sigma1"] for t in r["tests"]])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
    xs = np.linspace(0, s3.max() * 1.1, 50)
    a1.plot(s3 / MPA, s1 / MPA, "o", color="C0", ms=5, label="peaks")
    a1.plot(xs / MPA, sigma1_from_mc(xs, fit["phi"], fit["cohesion"]) / MPA, "-", color="C0",
            label=rf"fit: $\phi$ {fit['phi']:.1f}$\pm${_f(fit['phi_err'], 2)}°, C {fit['cohesion'] / MPA:.2f}"
                  rf"$\pm${_f(fit['cohesion_err'] / MPA, 2)} MPa")
    if targets:
        a1.plot(xs / MPA, sigma1_from_mc(xs, targets["phi"], targets["cohesion"]) / MPA, "--", color="C3",
                lw=1, label=rf"target: $\phi$ {targets['phi']:g}°, C {targets['cohesion'] / MPA:g} MPa")
    res = r.get("residual_fit")
    if res:
        rs3 = np.array([t["peak"]["residual_sigma3"] for t in r["tests"]])
        rs1 = np.array([t["peak"]["residual_sigma1"] for t in r["tests"]])
        a1.plot(rs3 / MPA, rs1 / MPA, "s", color="0.5", ms=3, label=rf"residual: $\phi$ {res['phi']:.1f}°, "
                                                                      rf"C {res['cohesion'] / MPA:.2f} MPa")
    a1.set_xlabel(r"$\sigma_3$ (MPa)")
    a1.set_ylabel(r"$\sigma_1$ at peak (MPa)")
    a1.legend(fontsize=7)
    a1.set_xlim(left=0)
    a1.set_ylim(bottom=0)
    # Mohr circles of the peaks and the envelope tau = C + sigma tan(phi)
    th = np.linspace(0, np.pi, 60)
    for a, b in zip(s3, s1):
        c, rad = 0.5 * (a + b), 0.5 * (b - a)
        a2.plot((c + rad * np.cos(th)) / MPA, rad * np.sin(th) / MPA, color="C0", lw=0.6)
    sig = np.linspace(0, s1.max() * 1.05, 50)
    a2.plot(sig / MPA, (fit["cohesion"] + sig * math.tan(math.radians(fit["phi"]))) / MPA, color="C0", label="fit")
    if targets:
        a2.plot(sig / MPA, (targets["cohesion"] + sig * math.tan(math.radians(targets["phi"]))) / MPA, "--",
                color="C3", lw=1, label="target")
    a2.set_aspect("equal")
    a2.set_xlim(0, s1.max() / MPA * 1.05)
    a2.set_ylim(0, 0.6 * s1.max() / MPA)
    a2.set_xlabel(r"$\sigma_n$ (MPa)")
    a2.set_ylabel(r"$\tau$ (MPa)")
    a2.legend(fontsize=7)
    a2.set_title("Mohr circles at peak", fontsize=10)
    return _save(fig, path)


def matched_comparison(bx: dict) -> List[str]:
    """Sets that differ from the set `full` only by the inertia factor, on a
    subset of its packs: the fit of `full` over the same packs beside them
    (the scatter between packs is larger than the effect looked for)."""
    from .fit import mohr_coulomb_fit
    full = bx.get("full")
    if not full:
        return []
    rows = []
    for label, r in bx.items():
        if label == "full" or r["sample"]["rmin"] != full["sample"]["rmin"] or \
                r["sample"]["W"] != full["sample"]["W"] or r["sample"].get("dist") != full["sample"].get("dist") or \
                r["sample"].get("dim", 2) != full["sample"].get("dim", 2):
            continue
        seeds = {t["seed"] for t in r["tests"]}
        same = [t for t in full["tests"] if t["seed"] in seeds and
                t["sigma3_target"] in {u["sigma3_target"] for u in r["tests"]}]
        if len(same) != len(r["tests"]):
            continue
        m = mohr_coulomb_fit([t["peak"]["sigma3"] for t in same], [t["peak"]["sigma1"] for t in same])
        f = r["fit"]
        rows.append([f"`{label}` (S {_f(r.get('inertia', 1.0))})", ", ".join(sorted(seeds)),
                     f"{f['phi']:.2f} +- {_f(f['phi_err'], 2)}", f"{m.phi:.2f} +- {_f(m.phi_err, 2)}",
                     f"{f['cohesion'] / MPA:.3f} +- {_f(f['cohesion_err'] / MPA, 2)}",
                     f"{m.cohesion / MPA:.3f} +- {_f(m.cohesion_err / MPA, 2)}"])
    if not rows:
        return []
    return ["Pack for pack against the set `full` (same packs and confinements, S = 1):", ""] + _table(
        ["set", "packs", "phi (deg)", "phi of `full`, same packs", "C (MPa)", "C of `full`, same packs"], rows)


def biaxial_section(out: Path, label: str, r: dict, targets: Optional[dict]) -> List[str]:
    s, f, m = r["sample"], r["fit"], r["material"]
    d3 = s.get("dim", 2) == 3
    L = [f"### Biaxial set `{label}`" + (" (3D triaxial tests)" if d3 else ""), "",
         f"Packs of {s['W']:g} m x {s['H']:g} m" + (f" x {s['D']:g} m" if d3 else "") +
         f" (tools/pack.in, seeds {', '.join(str(x) for x in s['seeds'])}), "
         f"radii {s['rmin']:g}-{s['rmax']:g} m ({s.get('dist', 'uniform')} distribution), {min(t['discs'] for t in r['tests'])}-"
         f"{max(t['discs'] for t in r['tests'])} {'spheres' if d3 else 'discs'} per sample; axial strain "
         f"rate {r['erate']:.3g} 1/s to {100 * r['strain_max']:g} %; cover inertia factor "
         f"S = {r.get('inertia', 1.0):g}; {len(r['tests'])} tests, "
         f"{r['seconds']:.0f} s of lmp time in all.", "",
         "Micro-parameters: " + ", ".join(f"{k} {_f(v)}" for k, v in m.items()) + ".", ""]
    rows = []
    for t in sorted(r["tests"], key=lambda t: (t["sigma3_target"], t["seed"])):
        p = t["peak"]
        rows.append([_f(t["sigma3_target"] / MPA), t["seed"], t["discs"], f"{100 * p['axial']:.2f}",
                     f"{p['sigma3'] / MPA:.3f}", f"{p['sigma1'] / MPA:.2f}", f"{p['q'] / MPA:.2f}",
                     f"{p['residual_sigma1'] / MPA:.2f}", "yes" if p["reached"] else "**no**"])
    L += _table(["sigma3 target (MPa)", "pack", "discs", "peak strain (%)", "sigma3 (MPa)", "sigma1 peak (MPa)",
                 "q peak (MPa)", "sigma1 residual (MPa)", "peak inside test"], rows)
    L += [f"**Mohr-Coulomb fit of the peaks** (sigma1 = N sigma3 + 2 C sqrt(N), least squares, standard errors "
          f"from the {f['n']} points): **phi = {f['phi']:.2f} +- {_f(f['phi_err'], 2)} deg** (tan phi = "
          f"{f['friction']:.3f}), **C = {f['cohesion'] / MPA:.3f} +- {_f(f['cohesion_err'] / MPA, 2)} MPa**, "
          f"N = {f['slope']:.3f}, rms misfit of sigma1 {f['rms'] / MPA:.2f} MPa.", ""]
    if r.get("residual_fit"):
        rf = r["residual_fit"]
        L += [f"Residual state (mean of the last 20 % of the strain): phi_res = {rf['phi']:.1f} deg, "
              f"C_res = {rf['cohesion'] / MPA:.2f} MPa.", ""]
    if targets:
        dphi, dc = f["phi"] - targets["phi"], (f["cohesion"] - targets["cohesion"]) / MPA
        L += [f"Against the targets (phi {targets['phi']:g} deg, C {targets['cohesion'] / MPA:g} MPa): "
              f"{dphi:+.2f} deg, {dc:+.3f} MPa.", ""]
    L += [f"![stress-strain]({plot_biaxial_curves(r, out / f'biaxial_{label}_curves.png')})", "",
          f"![Mohr-Coulomb]({plot_mohr(r, out / f'biaxial_{label}_mohr.png', targets)})", ""]
    return L


# -------------------------------------------------------------------- search

def plot_search(sr: dict, path: Path) -> str:
    knobs, pts = sr["knobs"], sr["points"]
    fig, axs = plt.subplots(1, 2, figsize=(9, 3.4))
    x = np.array([p["knobs"][knobs[0]] for p in pts])
    groups = sorted({p["knobs"][knobs[1]] for p in pts}) if len(knobs) > 1 else [None]
    for g in groups:
        sel = [i for i, p in enumerate(pts) if g is None or p["knobs"][knobs[1]] == g]
        lab = None if g is None else f"{knobs[1]} = {g:g}"
        for ax, key, sc, err in ((axs[0], "phi", 1.0, "phi_err"), (axs[1], "cohesion", MPA, "cohesion_err")):
            y = np.array([pts[i][key] for i in sel]) / sc
            e = np.array([pts[i][err] for i in sel], float) / sc
            ax.errorbar(x[sel], y, yerr=np.where(np.isfinite(e), e, 0), fmt="o-", ms=4, capsize=2, label=lab)
    t = sr["targets"]
    axs[0].axhline(t["phi"], color="C3", ls="--", lw=1)
    axs[1].axhline(t["cohesion"] / MPA, color="C3", ls="--", lw=1)
    axs[0].set_ylabel("phi (deg)")
    axs[1].set_ylabel("C (MPa)")
    for ax in axs:
        ax.set_xlabel(knobs[0])
        if len(knobs) > 1:
            ax.legend(fontsize=7)
    return _save(fig, path)


def search_section(out: Path, sr: dict) -> List[str]:
    knobs = sr["knobs"]
    L = ["## Search of the micro-parameters", "",
         "Each grid point is a biaxial set (all confinements and packs of the sample below) and its "
         "Mohr-Coulomb fit; the knob `cohesion` multiplies the contact cohesion, tensile strength and "
         "cohesive range of the starting material together.", "",
         "Starting material: " + ", ".join(f"{k} {_f(v)}" for k, v in sr["base"].items()) + ".", "",
         f"Sample: {sr['sample']['W']:g} m x {sr['sample']['H']:g} m, radii {sr['sample']['rmin']:g}-"
         f"{sr['sample']['rmax']:g} m, packs {sr['sample']['seeds']}, confinements "
         f"{', '.join(_f(c / MPA) for c in sr['sample']['confinements'])} MPa.", ""]
    rows = [[*(_f(p["knobs"][k]) for k in knobs), f"{p['phi']:.2f} +- {_f(p['phi_err'], 2)}",
             f"{p['cohesion'] / MPA:.3f} +- {_f(p['cohesion_err'] / MPA, 2)}"] for p in sr["points"]]
    L += _table([*knobs, "phi (deg)", "C (MPa)"], rows)
    sol = sr.get("solution")
    if sol:
        L += ["Planes through the grid points, phi = a.knobs + a0 and C = b.knobs + b0, solved for the targets "
              f"(phi {sr['targets']['phi']:g} deg, C {sr['targets']['cohesion'] / MPA:g} MPa): " +
              ", ".join(f"**{k} = {v:.4g}**" for k, v in sol["knobs"].items()) + ".", ""]
    L += [f"![search]({plot_search(sr, out / 'search.png')})", ""]
    return L


# -------------------------------------------------------------------- repose

def plot_repose(rp: dict, path: Path, out: Path) -> str:
    fig, ax = plt.subplots(figsize=(9, 3.2))
    dump = out / rp["dir"] / "repose_t.dump"
    if dump.exists():
        from matplotlib.collections import EllipseCollection
        a = np.loadtxt(dump, skiprows=9)
        d = 2 * a[:, 3]
        ax.add_collection(EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=a[:, 1:3],
                                            transOffset=ax.transData, facecolors="#f2c14e",
                                            edgecolors="#7a5c12", linewidths=0.2))
    ax.plot(rp["x"], rp["top"], ".", color="k", ms=3, label="surface (highest disc top per bin)")
    xs = np.array(rp["fit_range"])
    ax.plot(xs, rp["slope"] * xs + rp["intercept"], "-", color="C3", lw=1.5,
            label=f"fit: {rp['angle']:.1f} +- {rp['angle_err']:.1f} deg")
    ax.set_aspect("equal")
    ax.set_xlim(min(rp["x"]) - 50, max(rp["x"]) + 50)
    ax.set_ylim(-20, rp["height"] * 1.15)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, path)


def repose_section(out: Path, reps: dict) -> List[str]:
    L = ["## Angle of repose", "",
         "A block of cover discs (L0 x H0) on a rough floor is released on its right side and slumps into a "
         "heap; a line through the surface bins between 20 % and 80 % of the heap height gives the angle. "
         "With the calibrated cohesion a block of this size does not fail at all, so the test is run on the "
         "cohesionless assembly (cohesion x 0): it measures the friction of the packing alone.", ""]
    rows = []
    for k, rp in reps.items():
        rows.append([_f(rp["cohscale"]), f"{rp['size'][0]:g} x {rp['size'][1]:g}",
                     f"{rp['angle']:.1f} +- {rp['angle_err']:.1f}", f"{rp['height']:.0f}", rp["n_points"],
                     "**yes**" if rp["still_moving"] else "no"])
    L += _table(["cohesion x", "block (m)", "angle (deg)", "heap height (m)", "surface bins fitted",
                 "still moving at the end"], rows)
    for k, rp in reps.items():
        L += [f"![repose]({plot_repose(rp, out / f'repose_{k}.png', out)})", ""]
    return L


# ------------------------------------------------------------------- couette

def plot_couette(cr: dict, path: Path) -> str:
    eta0 = cr["salt"]["eta"]
    sweep = sorted([r for r in cr["runs"] if r["eta_in"] == eta0], key=lambda r: r["rate"])
    others = sorted([r for r in cr["runs"] if r["V"] == sweep[-1]["V"] or r["eta_in"] != eta0],
                    key=lambda r: r["eta_in"])
    fig, axs = plt.subplots(1, 3, figsize=(11, 3.4))
    g = np.array([r["rate"] for r in sweep])
    t = np.array([r["tau"] for r in sweep])
    axs[0].loglog(g, t, "o", color="C0", label="measured")
    gg = np.geomspace(g.min() / 1.5, g.max() * 1.5, 10)
    axs[0].loglog(gg, eta0 * gg, "--", color="C3", lw=1, label=rf"$\tau=\eta\dot\gamma$, $\eta$ = {eta0:g}")
    axs[0].set_xlabel(r"shear rate $\dot\gamma$ (1/s)")
    axs[0].set_ylabel(r"wall shear stress $\tau$ (Pa)")
    axs[0].legend(fontsize=7)
    axs[1].semilogx(g, [r["eta_eff"] / r["eta_in"] for r in sweep], "o-", color="C0")
    axs[1].axhspan(0.95, 1.05, color="C2", alpha=0.15, label="+-5 %")
    axs[1].axhline(1.0, color="0.5", lw=0.6)
    ratios = [r["eta_eff"] / r["eta_in"] for r in sweep]
    axs[1].set_ylim(min(0.9, min(ratios) - 0.02), max(1.1, max(ratios) + 0.02))
    axs[1].set_xlabel(r"shear rate $\dot\gamma$ (1/s)")
    axs[1].set_ylabel(r"$\eta_{eff}/\eta$")
    axs[1].legend(fontsize=7)
    ei = [r for r in cr["runs"] if r["V"] == cr.get("vref", None)] or others
    ein = np.array([r["eta_in"] for r in ei])
    eef = np.array([r["eta_eff"] for r in ei])
    o = np.argsort(ein)
    axs[2].plot(ein[o], eef[o], "o", color="C0", label="measured")
    xx = np.array([0, ein.max() * 1.1])
    axs[2].plot(xx, xx, "--", color="C3", lw=1, label=r"$\eta_{eff}=\eta$")
    axs[2].set_xlabel(r"input $\eta$ (Pa s)")
    axs[2].set_ylabel(r"$\eta_{eff}$ (Pa s)")
    axs[2].legend(fontsize=7)
    return _save(fig, path)


def plot_couette_profiles(cr: dict, path: Path) -> str:
    eta0 = cr["salt"]["eta"]
    fig, ax = plt.subplots(figsize=(4.5, 3.4))
    for r in sorted([r for r in cr["runs"] if r["eta_in"] == eta0], key=lambda r: r["V"]):
        y, vx = np.array(r["profile"]["y"]), np.array(r["profile"]["vx"])
        ax.plot(vx / r["V"], y, ".-", ms=3, lw=0.8, label=f"V {r['V']:g} m/s")
    lo, hi = cr["interior"]
    ax.axhspan(lo, hi, color="0.9", zorder=0, label="fitted interior")
    ax.set_xlabel(r"$v_x / V$")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7)
    return _save(fig, path)


def couette_section(out: Path, cr: dict) -> List[str]:
    s = cr["salt"]
    L = ["## Salt: plane Couette flow", "",
         f"examples/calibration/couette.in: the salt between two wall bands, the top band moving at V; "
         f"2 x {cr['nsteps']} steps, tau and the profile averaged over the last quarter (steps "
         f"{int(1.5 * cr['nsteps'])}-{2 * cr['nsteps']}); the shear rate is the slope of a line through the "
         f"profile layers {cr['interior'][0]:.0f}-{cr['interior'][1]:.0f} m (3 rmax off the wall bands).", "",
         f"Pack: {cr.get('pack_discs', '?')} discs, radius distribution '{cr.get('dist', '?')}' of tools/pack.in.", "",
         "Salt: " + ", ".join(f"{k} {_f(v)}" for k, v in s.items()) + " (S scaled with eta in the eta series).", ""]
    rows = []
    for r in sorted(cr["runs"], key=lambda r: (r["eta_in"], r["V"])):
        rows.append([_f(r["V"]), _f(r["eta_in"]), _f(r["S"]), _f(r["rate"]), _f(r["tau"]), _f(r["eta_eff"]),
                     f"{r['eta_eff'] / r['eta_in']:.4f}", f"{r['r2']:.5f}", f"{r['reynolds']:.3g}",
                     f"{r['tau'] / r['tau_first']:.3f}" if r.get("tau_first") else "-"])
    L += _table(["V (m/s)", "eta in (Pa s)", "S", "shear rate (1/s)", "tau (Pa)", "eta_eff (Pa s)",
                 "eta_eff/eta", "R^2 (linear profile)", "Re_S", "tau last/first window"], rows)
    nf = cr.get("newtonian")
    L += [f"Over the rate sweep (eta = {_f(s['eta'])} Pa s, {cr['rate_span']:.0f}x in shear rate): "
          f"**eta_eff/eta = {cr['ratio_mean']:.4f}** (max - min {cr['ratio_spread']:.4f})" +
          (f"; tau = eta' rate + tau0 gives eta' = {_f(nf['eta'])} Pa s, tau0 = {_f(nf['tau0'])} Pa; a power "
           f"law tau = k rate^n gives **n = {nf['n']:.4f}** (Newtonian: 1)." if nf else "."), ""]
    if cr.get("eta_input_for_target"):
        L += [f"Input viscosity for eta_eff = {_f(cr['target_eta'])} Pa s: **{_f(cr['eta_input_for_target'])} Pa s**.",
              ""]
    L += [f"![Couette]({plot_couette(cr, out / 'couette.png')})", "",
          f"![profiles]({plot_couette_profiles(cr, out / 'couette_profiles.png')})", ""]
    return L


def couette_checks_section(checks: dict) -> List[str]:
    rows = []
    for label, cr in checks.items():
        s = cr["salt"]
        for r in sorted(cr["runs"], key=lambda r: (r["eta_in"], r["V"])):
            rows.append([f"`{label}`", cr.get("dist", "-"), cr.get("pack_discs", "-"), _f(s["K_salt"]),
                         _f(s["h_salt"]), cr["nsteps"], _f(r["V"]), _f(r["eta_in"]), _f(r["S"]), _f(r["rate"]),
                         f"{r['eta_eff'] / r['eta_in']:.4f}", f"{r['reynolds']:.3g}",
                         f"{r['tau'] / r['tau_first']:.3f}" if r.get("tau_first") else "-"])
    return ["### Couette checks", ""] + _table(
        ["set", "radii", "discs", "K_salt (Pa)", "h_salt (m)", "steps per half", "V (m/s)", "eta in (Pa s)", "S",
         "shear rate (1/s)", "eta_eff/eta", "Re_S", "tau last/first window"], rows)


# -------------------------------------------------------------------- report

def _nan_errors(obj):
    """JSON stores NaN as null: give the standard errors (keys *_err) their NaN back."""
    if isinstance(obj, dict):
        return {k: (math.nan if (v is None and k.endswith("_err")) else _nan_errors(v)) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_nan_errors(v) for v in obj]
    return obj


def write_report(out: Path, res: dict) -> Path:
    out = Path(out)
    res = _nan_errors(res)
    targets = res.get("targets")
    L = ["# SaltDEM calibration report", "",
         f"Written by python/saltdem-calibrate ({res.get('updated', '')}). Stresses are compression-positive; "
         "sigma1 axial, sigma3 confining. +- values are standard errors.", ""]
    bx = res.get("biaxial", {})
    if bx:
        L += ["## Cover: biaxial tests", ""]
        summary = []
        for label, r in bx.items():
            f = r["fit"]
            summary.append([f"`{label}`", f"{r['sample']['rmin']:g}-{r['sample']['rmax']:g} "
                            f"{r['sample'].get('dist', 'uniform')}",
                            _f(r["material"].get("rscale_cover", 1)), _f(r.get("inertia", 1.0)), len(r["tests"]),
                            f"{f['phi']:.2f} +- {_f(f['phi_err'], 2)}",
                            f"{f['cohesion'] / MPA:.3f} +- {_f(f['cohesion_err'] / MPA, 2)}"])
        L += _table(["set", "radii (m)", "rscale_cover", "inertia S", "tests", "phi (deg)", "C (MPa)"], summary)
        L += matched_comparison(bx)
        for label, r in bx.items():
            L += biaxial_section(out, label, r, targets)
    if res.get("search"):
        L += search_section(out, res["search"])
    if res.get("repose"):
        L += repose_section(out, res["repose"])
    if res.get("couette"):
        L += couette_section(out, res["couette"])
    if res.get("couette_checks"):
        L += couette_checks_section(res["couette_checks"])
    if res.get("params_files"):
        L += ["## Parameter files", ""] + [f"- `{p}`" for p in res["params_files"]] + [""]
    path = out / "report.md"
    path.write_text("\n".join(L))
    return path
