/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the SaltDEM developers (USER-SALTDEM package, SaltDEM
   repository: discrete-element salt tectonics)
------------------------------------------------------------------------- */

#include "saltdem_viscous_args.h"

#include "saltdem_check.h"
#include "saltdem_contact_viscous.h"

#include "error.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

/* fluid ... [yield MU C] [modulus G]: the frictional-viscous fluid's strength C + MU P and the
   shear modulus of its plastic stress (default K: the stable step then follows a sound speed
   with K + 4G/3, 1.5x faster than K's alone) */

void parse_plastic(LAMMPS *lmp, const char *style, int narg, char **arg, SaltDEM::ViscousParams &p,
                   const char *usage)
{
  auto value = [&](const char *str, const char *what) {
    return SaltDEM::numeric(FLERR, str, fmt::format("Pair style {}: {}", style, what), lmp);
  };
  bool modulus = false;
  for (int k = 0; k < narg;) {
    if (strcmp(arg[k], "yield") == 0 && k + 3 <= narg) {
      p.mu_y = value(arg[k + 1], "yield MU");
      p.coh_y = value(arg[k + 2], "yield C");
      if (p.mu_y < 0.0 || p.coh_y < 0.0)
        lmp->error->all(FLERR, "Pair style {}: yield MU = {} and C = {} must be >= 0", style,
                        p.mu_y, p.coh_y);
      k += 3;
    } else if (strcmp(arg[k], "modulus") == 0 && k + 2 <= narg) {
      p.G = value(arg[k + 1], "modulus G");
      if (!(p.G > 0.0))
        lmp->error->all(FLERR, "Pair style {}: modulus G = {} must be > 0", style, p.G);
      modulus = true;
      k += 2;
    } else
      lmp->error->all(
          FLERR,
          "Pair style {}: unexpected or incomplete '{}' after 'fluid h K' (allowed: yield "
          "MU C, modulus G); usage: {}",
          style, arg[k], usage);
  }
  const bool yield = p.mu_y > 0.0 || p.coh_y > 0.0;
  if (modulus && !yield)
    lmp->error->all(
        FLERR,
        "Pair style {}: modulus G is the elastic part of a plastic strength: give yield "
        "MU C with MU or C > 0 too",
        style);
  if (yield && !(p.K > 0.0))
    lmp->error->all(FLERR,
                    "Pair style {}: yield needs a fluid that carries pressure (K > 0, got {}): its "
                    "strength C + MU P and its stress act through the pressure matrices",
                    style, p.K);
  if (yield && !modulus) p.G = p.K;
}

}    // namespace

/* pair_style saltdem/viscous [correction C] [calibration C] [dtfactor C] [viscfactor C]
   [fill F] [substeps N] [noslip centre|surface] [implicit yes|no] [tolerance T] [maxiter N] */

void SaltDEM::parse_viscous_settings(LAMMPS *lmp, const char *style, int narg, char **arg,
                                     ViscousSettings &s, double dtfactor_max, int max_substeps)
{
  int iarg = 0;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("pair_style {} {}", style, arg[iarg]), lmp->error);
    if (strcmp(arg[iarg], "substeps") == 0) {
      s.substeps = parse_viscous_substeps(lmp, style, arg[iarg + 1], max_substeps);
      iarg += 2;
      continue;
    }
    if (strcmp(arg[iarg], "noslip") == 0) {
      if (strcmp(arg[iarg + 1], "surface") == 0)
        s.noslip_surface = true;
      else if (strcmp(arg[iarg + 1], "centre") == 0 || strcmp(arg[iarg + 1], "center") == 0)
        s.noslip_surface = false;
      else
        lmp->error->all(FLERR,
                        "Pair style {}: noslip '{}' is not a boundary (expected surface: the fluid "
                        "meets a boundary disc at its surface, or centre: at its centre)",
                        style, arg[iarg + 1]);
      iarg += 2;
      continue;
    }
    if (strcmp(arg[iarg], "implicit") == 0) {
      if (strcmp(arg[iarg + 1], "yes") != 0 && strcmp(arg[iarg + 1], "no") != 0)
        lmp->error->all(FLERR,
                        "Pair style {}: implicit '{}' must be yes (the viscosity in an implicit "
                        "step, no viscous step limit) or no",
                        style, arg[iarg + 1]);
      s.implicit = strcmp(arg[iarg + 1], "yes") == 0;
      iarg += 2;
      continue;
    }
    if (strcmp(arg[iarg], "maxiter") == 0) {
      s.maxiter = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (s.maxiter < 1 || s.maxiter > 100000)
        lmp->error->all(FLERR, "Pair style {}: maxiter {} must be in [1, 100000]", style,
                        s.maxiter);
      iarg += 2;
      continue;
    }
    const double v = SaltDEM::numeric(FLERR, arg[iarg + 1],
                                      fmt::format("Pair style {}: {}", style, arg[iarg]), lmp);
    if (strcmp(arg[iarg], "correction") == 0) {
      if (v <= 0.0) lmp->error->all(FLERR, "Pair style {}: correction {} must be > 0", style, v);
      s.correction = v;
    } else if (strcmp(arg[iarg], "calibration") == 0) {
      if (v <= 0.0) lmp->error->all(FLERR, "Pair style {}: calibration {} must be > 0", style, v);
      s.calibration = v;
    } else if (strcmp(arg[iarg], "dtfactor") == 0) {
      if (v <= 0.0 || v > dtfactor_max)
        lmp->error->all(FLERR, "Pair style {}: dtfactor {} must be in (0, {}]", style, v,
                        dtfactor_max);
      s.dtfactor = v;
    } else if (strcmp(arg[iarg], "viscfactor") == 0) {
      if (v <= 0.0 || v > 1.0)
        lmp->error->all(FLERR, "Pair style {}: viscfactor {} must be in (0, 1]", style, v);
      s.viscfactor = v;
    } else if (strcmp(arg[iarg], "fill") == 0) {
      if (v < 1.0 || v > 100.0)
        lmp->error->all(FLERR,
                        "Pair style {}: fill {} must be in [1, 100] (the most a boundary particle "
                        "stands for, in its own volumes; 1: none)",
                        style, v);
      s.fill_max = v;
    } else if (strcmp(arg[iarg], "tolerance") == 0) {
      if (!(v > 0.0 && v < 1.0))
        lmp->error->all(FLERR,
                        "Pair style {}: tolerance {} must be in (0, 1) (the implicit step's "
                        "residual over the net force at the start velocities)",
                        style, v);
      s.tolerance = v;
    } else
      lmp->error->all(FLERR,
                      "Pair style {}: unknown keyword '{}' (expected: correction, calibration, "
                      "dtfactor, viscfactor, fill, substeps, noslip, implicit, tolerance, "
                      "maxiter)",
                      style, arg[iarg]);
    iarg += 2;
  }
}

int SaltDEM::parse_viscous_substeps(LAMMPS *lmp, const char *style, const char *str,
                                    int max_substeps)
{
  const int n = utils::inumeric(FLERR, str, false, lmp);
  if (n < 1 || n > max_substeps)
    lmp->error->all(
        FLERR, "Pair style {}: substeps {} must be in [1, {}] (1: the viscosity in the force pass)",
        style, n, max_substeps);
  return n;
}

/* pair_coeff I J eta kn fluid h K [yield MU C] [modulus G]
   pair_coeff I J eta kn contact gap [tangential ratio] */

SaltDEM::ViscousParams SaltDEM::parse_viscous_coeff(LAMMPS *lmp, const char *style, int narg,
                                                    char **arg, const char *usage, double &eta)
{
  SaltDEM::ViscousParams p{};
  auto value = [&](const char *str, const char *what) {
    return SaltDEM::numeric(FLERR, str, fmt::format("Pair style {}: {}", style, what), lmp);
  };
  eta = value(arg[2], "eta");
  p.kn = value(arg[3], "kn");
  if (eta <= 0.0) lmp->error->all(FLERR, "Pair style {}: eta = {} must be > 0", style, eta);
  if (p.kn < 0.0) lmp->error->all(FLERR, "Pair style {}: kn = {} must be >= 0", style, p.kn);
  p.ratio = 1.0;

  std::string kw = arg[4];
  if (kw == "fluid") {
    p.mode = SaltDEM::VISCOUS_FLUID;
    p.h = value(arg[5], "fluid h");
    if (p.h <= 0.0) lmp->error->all(FLERR, "Pair style {}: fluid h = {} must be > 0", style, p.h);
    if (narg < 7)
      lmp->error->all(FLERR, "Pair style {}: 'fluid' takes h and K, got {} values; usage: {}",
                      style, narg - 5, usage);
    p.K = value(arg[6], "fluid K");
    if (p.K < 0.0) lmp->error->all(FLERR, "Pair style {}: fluid K = {} must be >= 0", style, p.K);
    parse_plastic(lmp, style, narg - 7, arg + 7, p, usage);
  } else if (kw == "contact") {
    p.mode = SaltDEM::VISCOUS_CONTACT;
    if (p.kn <= 0.0)
      lmp->error->all(FLERR,
                      "Pair style {}: contact kn = {} must be > 0 (a boundary needs its elastic "
                      "repulsion)",
                      style, p.kn);
    p.gap = value(arg[5], "contact gap");
    if (p.gap < 0.0)
      lmp->error->all(FLERR, "Pair style {}: contact gap = {} must be >= 0", style, p.gap);
    if (narg == 8 && strcmp(arg[6], "tangential") == 0) {
      p.ratio = value(arg[7], "tangential ratio");
      if (p.ratio < 0.0)
        lmp->error->all(FLERR, "Pair style {}: tangential ratio = {} must be >= 0", style, p.ratio);
    } else if (narg != 6)
      lmp->error->all(FLERR,
                      "Pair style {}: unexpected arguments after 'contact {}' (allowed: "
                      "tangential R); usage: {}",
                      style, arg[5], usage);
  } else
    lmp->error->all(FLERR, "Pair style {}: unknown law '{}' (expected fluid or contact); usage: {}",
                    style, kw, usage);

  return p;
}

std::vector<std::string> SaltDEM::viscous_setting_names(int layout)
{
  if (layout == 1) return {"calibration", "correction", "dtfactor", "viscfactor"};
  if (layout == 3)
    return {"calibration", "correction", "dtfactor", "viscfactor", "fill", "substeps"};
  if (layout == 4 || layout == 5)
    return {"calibration", "correction", "dtfactor", "viscfactor", "fill", "substeps", "noslip"};
  return {"calibration", "correction", "dtfactor", "viscfactor", "fill",
          "substeps",    "noslip",     "implicit", "tolerance",  "maxiter"};
}

void SaltDEM::pack_viscous_settings(const ViscousSettings &s, double *v)
{
  v[0] = s.calibration;
  v[1] = s.correction;
  v[2] = s.dtfactor;
  v[3] = s.viscfactor;
  v[4] = s.fill_max;
  v[5] = s.substeps;
  v[6] = s.noslip_surface ? 1.0 : 0.0;
  v[7] = s.implicit ? 1.0 : 0.0;
  v[8] = s.tolerance;
  v[9] = s.maxiter;
}

void SaltDEM::unpack_viscous_settings(const double *v, int layout, double default_fill,
                                      ViscousSettings &s)
{
  s.calibration = v[0];
  s.correction = v[1];
  s.dtfactor = v[2];
  s.viscfactor = v[3];
  s.fill_max = (layout == 1) ? default_fill : v[4];
  s.substeps = (layout == 1) ? 1 : (int) v[5];
  s.noslip_surface = (layout >= 4) && v[6] != 0.0;
  const bool has_implicit = layout == 0 || layout >= 6;
  s.implicit = has_implicit && v[7] != 0.0;
  if (has_implicit) {
    s.tolerance = v[8];
    s.maxiter = (int) v[9];
  }
}

/* the law, the viscosity and the coefficients given (the dashpots cw, ih2, kfac, gn, gt are
   derived); the plastic strength came with layout 5 */

std::vector<std::string> SaltDEM::viscous_coeff_names(int layout)
{
  if (layout > 0 && layout < 5) return {"law", "eta", "kn", "h", "K", "gap", "tangential"};
  return {"law", "eta", "kn", "h", "K", "gap", "tangential", "yield_mu", "yield_c", "modulus"};
}

void SaltDEM::pack_viscous_coeff(const ViscousParams &p, double eta, double *v)
{
  const double f[] = {(double) p.mode, eta, p.kn, p.h, p.K, p.gap, p.ratio, p.mu_y, p.coh_y, p.G};
  for (int k = 0; k < 10; k++) v[k] = f[k];
}

void SaltDEM::unpack_viscous_coeff(const double *v, int n, ViscousParams &p, double &eta)
{
  p = ViscousParams{};
  p.mode = (v[0] == VISCOUS_CONTACT) ? VISCOUS_CONTACT : VISCOUS_FLUID;
  eta = v[1];
  p.kn = v[2];
  p.h = v[3];
  p.K = v[4];
  p.gap = v[5];
  p.ratio = v[6];
  if (n >= 10) {
    p.mu_y = v[7];
    p.coh_y = v[8];
    p.G = v[9];
  }
}
