"""What the calibration writes: ``results.json`` with the report rebuilt from
it, and the parameter files of a calibrated cover and salt."""

from __future__ import annotations

import datetime
import json
from pathlib import Path
from typing import Dict, Optional

from ..output import ensure_dir, write_json
from .experiments import COVER_NAMES, MPA, SALT_NAMES, SCALED
from .runner import CalibrationError, Context, say


def load_results(ctx: Context) -> dict:
    p = ctx.out / "results.json"
    return json.loads(p.read_text()) if p.exists() else {}


def save_results(ctx: Context, results: dict) -> None:
    results["updated"] = datetime.datetime.now().isoformat(timespec="seconds")
    write_json(str(ctx.out / "results.json"), results)
    from .report import write_report
    path = write_report(ctx.out, results)
    say(f"report: {path}")


# --------------------------------------------------------------- parameters

def params_text_cover(material: Dict[str, float], result: Optional[dict], quick: Optional[dict],
                      repose: Optional[dict], name: str, command: str) -> str:
    rs = material.get("rscale_cover", 1.0)
    base = {k: (material[k] / rs if k in SCALED else material[k]) for k in COVER_NAMES if k != "rscale_cover"}
    L = [f"# SaltDEM parameters: the {name} cover - frictional-cohesive, pair style saltdem/cohesive",
         "# (elastic + reversible cohesion + Mohr-Coulomb tangential spring + rolling resistance).",
         "#",
         "#   include /path/to/potentials/cover_" + name + ".params     # before the deck's own definitions",
         "#   pair_coeff 1 1 saltdem/cohesive ${kn_cover} ${kt_cover} ${mu_cover} ${coh_cover} ${ten_cover} &",
         "#              ${rng_cover} damp ${zn_cover} ${zt_cover} rolling ${kr_cover} ${mur_cover}",
         "#",
         "# Every line is an 'index' variable: a value given on the command line or defined earlier wins.",
         "# Size rule (2D, unit thickness): stiffnesses (N/m), friction and damping ratios are independent",
         "# of the disc size; the contact cohesion and tensile strength (forces, N) and the cohesive range",
         "# (a gap, m) scale with the disc radius.  They are given for radii 6.25-15.625 m times",
         "# rscale_cover: set 'variable rscale_cover index 4' before the include for discs 4x larger",
         "# (25-62.5 m).",
         f"# Measured with: {command}"]
    if result:
        f = result["fit"]
        L.append(f"# measured: phi {f['phi']:.2f} +- {f['phi_err']:.2f} deg, C {f['cohesion'] / MPA:.3f} +- "
                 f"{f['cohesion_err'] / MPA:.3f} MPa (biaxial, radii {result['sample']['rmin']:g}-"
                 f"{result['sample']['rmax']:g} m, {len(result['tests'])} tests)")
    if quick:
        f = quick["fit"]
        L.append(f"# measured: phi {f['phi']:.2f} +- {f['phi_err']:.2f} deg, C {f['cohesion'] / MPA:.3f} +- "
                 f"{f['cohesion_err'] / MPA:.3f} MPa (biaxial, radii {quick['sample']['rmin']:g}-"
                 f"{quick['sample']['rmax']:g} m, rscale_cover {quick['material']['rscale_cover']:g})")
    if repose:
        L.append(f"# measured: angle of repose {repose['angle']:.1f} +- {repose['angle_err']:.1f} deg "
                 f"(cohesion x {repose['cohscale']:g})")
    L.append("")
    doc = {
        "rscale_cover": "disc radii / (6.25-15.625 m)",
        "kn_cover": "N/m: normal contact stiffness",
        "kt_cover": "N/m: tangential contact stiffness",
        "mu_cover": "contact friction coefficient",
        "coh_cover": "N: contact cohesion (shear strength at zero normal force), x rscale_cover",
        "ten_cover": "N: contact tensile strength, x rscale_cover",
        "rng_cover": "m: gap at which the attraction vanishes, x rscale_cover",
        "zn_cover": "normal damping ratio (fraction of critical)",
        "zt_cover": "tangential damping ratio",
        "kr_cover": "N/m: rolling stiffness",
        "mur_cover": "rolling friction coefficient",
    }
    L.append(f"variable        {'rscale_cover':<13} index 1         # {doc['rscale_cover']}")
    for k, v in base.items():
        val = f"$({v:.6g}*v_rscale_cover)" if k in SCALED else f"{v:.6g}"
        L.append(f"variable        {k:<13} index {val:<9} # {doc[k]}")
    return "\n".join(L) + "\n"


def params_text_salt(salt: Dict[str, float], couette: dict, name: str, command: str) -> str:
    L = [f"# SaltDEM parameters: the {name} salt - linear Newtonian viscous, pair style saltdem/viscous",
         "# (fluid law salt-salt), integrated by fix saltdem/nve inertia ${S}.",
         "#",
         f"#   include /path/to/potentials/salt_{name}.params",
         "#",
         f"# Measured with: {command}",
         f"# measured: eta_eff / eta = {couette['ratio_mean']:.4f} (spread {couette['ratio_spread']:.4f}) over "
         f"{couette['rate_span']:.0f}x in shear rate, plane Couette"]
    if couette.get("newtonian"):
        L.append(f"# measured: power-law index n = {couette['newtonian']['n']:.4f}, tau0 = "
                 f"{couette['newtonian']['tau0']:.4g} Pa")
    L.append("")
    for k in SALT_NAMES:
        L.append(f"variable        {k:<13} index {salt[k]:.6g}")
    return "\n".join(L) + "\n"


def write_params(path: Path, text: str, force: bool) -> Path:
    if path.exists() and not force:
        raise CalibrationError(f"{path} exists: choose another --name or add --force")
    ensure_dir(str(path.parent))
    path.write_text(text)
    return path
