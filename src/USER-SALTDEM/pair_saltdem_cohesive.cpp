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

   pair saltdem/cohesive: the frictional-cohesive cover.  The law itself is
   SaltDEM::cohesive_force (saltdem_contact_cohesive.h); this file parses and checks
   its coefficients, mixes cross types and sets the stable time step.
------------------------------------------------------------------------- */

#include "pair_saltdem_cohesive.h"

#include "saltdem_check.h"
#include "saltdem_cohesive_law.h"
#include "saltdem_contact_cohesive.h"
#include "saltdem_pair_loop.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

PairSaltdemCohesive::PairSaltdemCohesive(LAMMPS *lmp) :
    PairSaltdem(lmp, "saltdem/cohesive", "SALTDEM_COHESIVE_HISTORY"), params(nullptr),
    rolling(false), dt(0.0)
{
  size_history = 3;
}

PairSaltdemCohesive::~PairSaltdemCohesive()
{
  if (copymode) return;
  memory->destroy(params);
}

void PairSaltdemCohesive::allocate_params(int n)
{
  memory->create(params, n + 1, n + 1, "pair:params");
  memset(&params[0][0], 0, sizeof(SaltDEM::CohesiveParams) * (n + 1) * (n + 1));
}

/* ---------------------------------------------------------------------- */

void PairSaltdemCohesive::compute(int eflag, int vflag)
{
  compute_serial(law(), eflag, vflag);
}

SaltDEM::CohesiveLaw PairSaltdemCohesive::law() const
{
  return {params, rolling, dt};
}

void *PairSaltdemCohesive::pair_params(int i, int j)
{
  return &params[i][j];
}

size_t PairSaltdemCohesive::params_size() const
{
  return sizeof(SaltDEM::CohesiveParams);
}

/* the attraction acts up to range beyond contact (with a tensile strength) */

double PairSaltdemCohesive::range(int i, int j) const
{
  return params[i][j].tens > 0.0 ? params[i][j].range : 0.0;
}

/* pair_style saltdem/cohesive [dtfactor C] */

void PairSaltdemCohesive::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "dtfactor") == 0) {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, fmt::format("pair_style {} dtfactor", name), error);
      dtfactor =
          SaltDEM::numeric(FLERR, arg[iarg + 1], fmt::format("Pair style {}: dtfactor", name), lmp);
      if (dtfactor <= 0.0 || dtfactor > DTFACTOR_MAX)
        error->all(FLERR, "Pair style {}: dtfactor {} must be in (0, {}]", name, dtfactor,
                   DTFACTOR_MAX);
      iarg += 2;
    } else
      error->all(FLERR, "Pair style {}: unknown keyword '{}' (expected: dtfactor)", name,
                 arg[iarg]);
  }
}

/* pair_coeff I J kn kt mu cohesion tensile range [damp zn zt] [rolling kr mur] */

void PairSaltdemCohesive::coeff(int narg, char **arg)
{
  const char *usage = "pair_coeff I J kn kt mu cohesion tensile range [damp zeta_n zeta_t] "
                      "[rolling kr mu_r]";
  int ilo, ihi, jlo, jhi;
  check_types(narg, arg, 8, usage, ilo, ihi, jlo, jhi);

  SaltDEM::CohesiveParams p{};
  auto value = [&](const char *str, const char *what) {
    return SaltDEM::numeric(FLERR, str, fmt::format("Pair style {}: {}", name, what), lmp);
  };
  p.kn = value(arg[2], "kn");
  p.kt = value(arg[3], "kt");
  p.mu = value(arg[4], "mu");
  p.coh = value(arg[5], "cohesion");
  p.tens = value(arg[6], "tensile");
  p.range = value(arg[7], "range");

  auto positive = [&](double v, const char *what, bool strict) {
    if (v < 0.0 || (strict && v == 0.0))
      error->all(FLERR, "Pair style {}: {} = {} must be {}", name, what, v,
                 strict ? "> 0" : ">= 0");
  };
  positive(p.kn, "kn", true);
  positive(p.kt, "kt", false);
  positive(p.mu, "mu", false);
  positive(p.coh, "cohesion", false);
  positive(p.tens, "tensile", false);
  positive(p.range, "range", false);

  int iarg = 8;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "damp") == 0) {
      if (iarg + 3 > narg)
        utils::missing_cmd_args(FLERR, fmt::format("pair_coeff {} damp", name), error);
      p.zeta_n = value(arg[iarg + 1], "damp zeta_n");
      p.zeta_t = value(arg[iarg + 2], "damp zeta_t");
      if (p.zeta_n < 0.0 || p.zeta_n >= 1.0 || p.zeta_t < 0.0 || p.zeta_t >= 1.0)
        error->all(FLERR, "Pair style {}: damping ratios {} {} must be in [0, 1)", name, p.zeta_n,
                   p.zeta_t);
      iarg += 3;
    } else if (strcmp(arg[iarg], "rolling") == 0) {
      if (iarg + 3 > narg)
        utils::missing_cmd_args(FLERR, fmt::format("pair_coeff {} rolling", name), error);
      p.kr = value(arg[iarg + 1], "rolling kr");
      p.mur = value(arg[iarg + 2], "rolling mu_r");
      positive(p.kr, "rolling kr", false);
      positive(p.mur, "rolling mu_r", false);
      iarg += 3;
    } else
      error->all(FLERR, "Pair style {}: unknown pair_coeff keyword '{}'; usage: {}", name,
                 arg[iarg], usage);
  }
  if (p.tens > 0.0 && p.range <= p.tens / p.kn)
    error->all(FLERR,
               "Pair style {}: range {} must exceed the elastic gap tensile/kn = {} at which the "
               "attraction peaks",
               name, p.range, p.tens / p.kn);

  // the damping coefficients must be finite (init_one derives them again)
  SaltDEM::cohesive_derive(p, force->ftm2v);
  if (!std::isfinite(p.cn) || !std::isfinite(p.ct))
    error->all(FLERR,
               "Pair style {}: the damping coefficients 2 zeta sqrt(k) = {} {} from kn = "
               "{}, kt = {} and damp {} {} are not finite",
               name, p.cn, p.ct, p.kn, p.kt, p.zeta_n, p.zeta_t);
  assign_coeffs(ilo, ihi, jlo, jhi, [&](int i, int j) {
    params[i][j] = p;
  });
}

/* cross types: springs in series, strengths by geometric mean (an interface
   with a cohesionless or frictionless side has none), the rest averaged */

void PairSaltdemCohesive::mix(int i, int j)
{
  const auto &a = params[i][i];
  const auto &b = params[j][j];
  SaltDEM::CohesiveParams &p = params[i][j];
  p.kn = mix_series(a.kn, b.kn);
  p.kt = mix_series(a.kt, b.kt);
  p.kr = mix_series(a.kr, b.kr);
  p.mu = sqrt(a.mu * b.mu);
  p.coh = sqrt(a.coh * b.coh);
  p.tens = sqrt(a.tens * b.tens);
  p.mur = sqrt(a.mur * b.mur);
  p.range = 0.5 * (a.range + b.range);
  p.zeta_n = 0.5 * (a.zeta_n + b.zeta_n);
  p.zeta_t = 0.5 * (a.zeta_t + b.zeta_t);
  if (p.tens > 0.0 && p.range <= p.tens / p.kn) p.range = 1.01 * p.tens / p.kn;
}

/* the damping coefficients per sqrt(reduced mass) */

void PairSaltdemCohesive::derive(int i, int j)
{
  SaltDEM::cohesive_derive(params[i][j], force->ftm2v);
}

/* ---------------------------------------------------------------------- */

void PairSaltdemCohesive::init_style()
{
  // the rolling history needs 3 more values; fixed once the history exists
  bool want = false;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && params[i][j].kr > 0.0) want = true;
  if (fix_history && want != rolling)
    error->all(FLERR,
               "Pair style {}: rolling resistance was {} after the first run; set it "
               "before the first run (or issue 'pair_style none' and define the pair style again)",
               name, want ? "switched on" : "switched off");
  rolling = want;
  size_history = rolling ? 6 : 3;
  delete[] transfer_factor;
  transfer_factor = new double[size_history];
  // seen from j the tangential displacement flips sign and the rolling displacement does not;
  // in 2D both are kept as lengths along the tangent (-n1, n0), which flips too
  // (saltdem_contact_cohesive.h)
  const bool dim2 = (domain->dimension == 2);
  for (int k = 0; k < size_history; k++) transfer_factor[k] = ((k < 3) != dim2) ? -1.0 : 1.0;
  nondefault_history_transfer = 1;

  dt = update->dt;
  PairSaltdem::init_style();
}

/* The stiffest oscillator of the pair: the normal spring, or the tangential spring that also
   turns the disc (SaltDEM::rotation_factor).  Stable dt = C * sqrt(m_min / k), with k in
   mass / time^2 (times ftm2v: 1 in SI), C = dtfactor (2 dtfactor against a wall). */

void PairSaltdemCohesive::pair_limit(int i, int j, double m, double, bool wall, double &best,
                                     std::string &why)
{
  const double rot = SaltDEM::rotation_factor(domain->dimension);
  const auto &p = params[i][j];
  const bool tang = rot * p.kt > p.kn;
  const double k = tang ? rot * p.kt : p.kn;
  const double c = elastic_factor(wall);
  consider_limit(c * sqrt(m / (k * force->ftm2v)), best, why, [&] {
    return fmt::format("{} = {:.6g} of types {} {} with the lightest mass {:.6g} "
                       "(dt < {} * sqrt(m/{}){})",
                       tang ? "kt" : "kn", tang ? p.kt : p.kn, i, j, m, c,
                       tang ? fmt::format("({}*kt)", rot) : "kn",
                       wall ? ", 2 dtfactor against a wall" : "");
  });
}

/* ---------------------------------------------------------------------- */

/* the restart fields of a type pair: the coefficients given (cn, ct are derived) */

std::vector<std::string> PairSaltdemCohesive::coeff_names() const
{
  return {"kn", "kt", "mu", "cohesion", "tensile", "range", "zeta_n", "zeta_t", "kr", "mu_r"};
}

void PairSaltdemCohesive::pack_coeffs(int i, int j, double *v) const
{
  const auto &p = params[i][j];
  const double f[] = {p.kn, p.kt, p.mu, p.coh, p.tens, p.range, p.zeta_n, p.zeta_t, p.kr, p.mur};
  for (int k = 0; k < 10; k++) v[k] = f[k];
}

void PairSaltdemCohesive::unpack_coeffs(int i, int j, const double *v)
{
  SaltDEM::CohesiveParams p{};
  p.kn = v[0];
  p.kt = v[1];
  p.mu = v[2];
  p.coh = v[3];
  p.tens = v[4];
  p.range = v[5];
  p.zeta_n = v[6];
  p.zeta_t = v[7];
  p.kr = v[8];
  p.mur = v[9];
  params[i][j] = p;
}

/* kn etc. for fixes and computes: per type pair arrays are not exposed;
   the scalar "dtfactor" is */

void *PairSaltdemCohesive::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "dtfactor") == 0) return (void *) &dtfactor;
  return nullptr;
}
