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

   fix saltdem/viscosity: viscosity scaling (Hardy's section 2.1).  The
   model runs with eta_model = eta_natural / lambda, so its velocities are
   lambda times the natural ones, its time 1/lambda of the natural time, and
   Re_model = lambda^2 Re_natural.  The fix sets the viscosity of every type
   pair of pair style saltdem/viscous (through Pair::extract("eta")) and
   reports the numbers that tie the model to nature; with a density contrast
   (keyword contrast) also the buoyancy stress drho g L against the viscous
   stress eta V / L.
------------------------------------------------------------------------- */

#include "fix_saltdem_viscosity.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_check.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemViscosity::FixSaltdemViscosity(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), lambda(0.0), eta_model(0.0), eta_natural(0.0), rate(0.0), length(0.0),
    density(0.0), contrast(0.0), gravity(0.0), inertia(1.0), inertia_given(0.0), warn_re(0.1),
    t0(0.0), npairs(0), reported(0.0), ftm2v(1.0), second(1.0), metre(1.0)
{
  // natural time in years and rates in m/ka need the deck's time and length in SI: from
  // LAMMPS's unit system (1 fs and 1 Angstrom in the deck's units); lj has none
  if (strcmp(update->unit_style, "lj") == 0)
    error->all(FLERR,
               "Fix {}: units lj have no physical time or length, so natural time in "
               "years and rates in m/ka cannot be reported; use units si (or another physical "
               "unit system)",
               style);
  ftm2v = force->ftm2v;
  second = 1.0e-15 / force->femtosecond;
  metre = 1.0e-10 / force->angstrom;

  const std::string usage = fmt::format("fix ID group {} lambda L (natural eta | model eta) rate "
                                        "V length L density rho [contrast drho [gravity g]] "
                                        "[inertia S] [warn Re]",
                                        style);
  if (narg < 5) utils::missing_cmd_args(FLERR, fmt::format("fix {}", style), error);
  if (strcmp(arg[3], "lambda") != 0)
    error->all(FLERR, "Fix {}: expected 'lambda' after the style, got '{}'; usage: {}", style,
               arg[3], usage);
  lambda = SaltDEM::numeric(FLERR, arg[4], fmt::format("Fix {}: lambda", style), lmp);
  if (lambda <= 0.0) error->all(FLERR, "Fix {}: lambda = {} must be > 0", style, lambda);

  int iarg = 5;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("fix {} {}", style, arg[iarg]), error);
    const std::string kw = arg[iarg];
    const double v =
        SaltDEM::numeric(FLERR, arg[iarg + 1], fmt::format("Fix {}: {}", style, kw), lmp);
    auto positive = [&](double x) {
      if (x <= 0.0) error->all(FLERR, "Fix {}: {} = {} must be > 0", style, kw, x);
      return x;
    };
    if (kw == "natural")
      eta_natural = positive(v);
    else if (kw == "model")
      eta_model = positive(v);
    else if (kw == "rate")
      rate = positive(v);
    else if (kw == "length")
      length = positive(v);
    else if (kw == "density")
      density = positive(v);
    else if (kw == "contrast") {
      if (v == 0.0)
        error->all(FLERR,
                   "Fix {}: contrast = 0: give the density of the overburden minus that of "
                   "the salt (negative when the salt is the denser), or leave the keyword out",
                   style);
      contrast = v;
    } else if (kw == "gravity")
      gravity = positive(v);
    else if (kw == "inertia") {
      if (v < 1.0) error->all(FLERR, "Fix {}: inertia = {} must be >= 1", style, v);
      inertia_given = v;
    } else if (kw == "warn")
      warn_re = positive(v);
    else
      error->all(FLERR, "Fix {}: unknown keyword '{}'; usage: {}", style, kw, usage);
    iarg += 2;
  }
  if ((eta_natural > 0.0) == (eta_model > 0.0))
    error->all(FLERR, "Fix {}: give exactly one of 'natural' and 'model'; usage: {}", style, usage);
  for (auto &need : {std::make_pair("rate", rate), std::make_pair("length", length),
                     std::make_pair("density", density)})
    if (need.second <= 0.0)
      error->all(FLERR, "Fix {}: keyword '{}' is required; usage: {}", style, need.first, usage);
  // g: 9.81 m/s^2 under si, given in the deck's units otherwise
  if (contrast != 0.0 && gravity == 0.0) {
    if (strcmp(update->unit_style, "si") != 0)
      error->all(FLERR,
                 "Fix {}: the buoyancy stress needs 'gravity g' in the deck's units (units "
                 "{}); the default 9.81 applies under units si only",
                 style, update->unit_style);
    gravity = 9.81;
  }
  if (gravity > 0.0 && contrast == 0.0)
    error->all(FLERR, "Fix {}: 'gravity' is used with 'contrast' only; usage: {}", style, usage);
  if (eta_natural > 0.0)
    eta_model = eta_natural / lambda;
  else
    eta_natural = eta_model * lambda;
  // the derived viscosities go to the pair style (its bounds) and the reported numbers must be
  // finite
  if (!SaltDEM::in_bounds(eta_model) || !SaltDEM::in_bounds(eta_natural))
    error->all(FLERR,
               "Fix {}: lambda = {} gives a model viscosity {} and a natural one {} "
               "beyond the bounds of SaltDEM coefficients [{:g}, {:g}]; check lambda and the "
               "viscosity given",
               style, lambda, eta_model, eta_natural, SaltDEM::MIN_VALUE, SaltDEM::MAX_VALUE);
  inertia = (inertia_given > 0.0) ? inertia_given : 1.0;
  check_finite();

  // set the viscosity of the salt's pair style now, so that the next run
  // (and its stable time step check) uses it: every saltdem/viscous sub-style of a hybrid
  const auto salts = PairSaltdem::saltdem_styles(lmp, "saltdem/viscous");
  if (salts.empty())
    error->all(FLERR,
               "Fix {} needs pair style saltdem/viscous (alone or in pair_style hybrid) "
               "with its coefficients set before the fix is defined",
               style);
  for (PairSaltdem *pair : salts) {
    int dim = 0;
    auto eta = (double **) pair->extract("eta", dim);
    if (!eta || dim != 2) continue;    // coefficients not allocated yet
    for (int i = 1; i <= atom->ntypes; i++)
      for (int j = i; j <= atom->ntypes; j++)
        if (pair->setflag && pair->setflag[i][j]) {
          eta[i][j] = eta[j][i] = eta_model;
          npairs++;
        }
  }
  if (npairs == 0)
    error->all(FLERR,
               "Fix {}: pair style saltdem/viscous needs its coefficients set before the "
               "fix is defined: give its pair_coeff commands first",
               style);
  // the inertia factor of the salt's discs as far as the integrators are defined yet (init()
  // reads it again): the Reynolds number is also wanted between runs
  if (inertia_given == 0.0) inertia = salt_inertia(salts, true);

  t0 = model_time();
  vector_flag = 1;
  size_vector = 12;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;

  if (comm->me == 0)
    utils::logmesg(lmp,
                   "fix {}: lambda {:.4g}: viscosity model {:.4g}, natural {:.4g} ({}) (set "
                   "on {} type pairs)\n",
                   style, lambda, eta_model, eta_natural, unit_label("Pa s"), npairs);
}

/* S: the inertia factor of the fix saltdem/nve integrating the salt's discs, as the salt's
   pair styles report it; the largest of several.  now: collective */

double FixSaltdemViscosity::salt_inertia(const std::vector<PairSaltdem *> &salts, bool now)
{
  double s = 1.0;
  for (PairSaltdem *pair : salts) {
    auto salt = dynamic_cast<PairSaltdemViscous *>(pair);
    int dim = 0;
    if (now && salt)
      s = MAX(s, salt->find_salt_inertia());
    else if (auto v = (double *) pair->extract("inertia", dim))
      s = MAX(s, *v);
  }
  return s;
}

/* the reported numbers must be finite and non-zero */

void FixSaltdemViscosity::check_finite()
{
  for (double q : {reynolds_model(), reynolds_natural(), natural_rate(), strain_rate_model(),
                   strain_rate_natural(), lambda * second / YEAR, viscous_stress()})
    if (!std::isfinite(q) || q == 0.0)
      error->all(FLERR,
                 "Fix {}: the Reynolds numbers, strain rates and time scale from lambda "
                 "= {}, rate = {}, length = {}, density = {}, inertia = {} and the viscosity {} "
                 "overflow or vanish ({}); use values of physical size",
                 style, lambda, rate, length, density, inertia, eta_model, q);
  if (contrast != 0.0)
    for (double q : {buoyancy_stress(), buoyancy_time(), reynolds_buoyancy()})
      if (!std::isfinite(q) || q == 0.0)
        error->all(FLERR,
                   "Fix {}: the buoyancy stress, time and Reynolds number from contrast = {}, "
                   "gravity = {}, length = {}, density = {}, inertia = {} and the viscosity {} "
                   "overflow or vanish ({}); use values of physical size",
                   style, contrast, gravity, length, density, inertia, eta_model, q);
}

int FixSaltdemViscosity::setmask()
{
  return 0;
}

/* S is read from the salt's pair style, which has it from the integrator: given once, in fix
   saltdem/nve.  The keyword 'inertia' may only repeat it. */

void FixSaltdemViscosity::init()
{
  const auto salts = PairSaltdem::saltdem_styles(lmp, "saltdem/viscous");
  if (salts.empty())
    error->all(FLERR,
               "Fix {} {} needs pair style saltdem/viscous (alone or in pair_style "
               "hybrid); the pair style was changed since the fix was defined",
               style, id);
  const double s = salt_inertia(salts, false);
  if (inertia_given > 0.0 && fabs(inertia_given - s) > 1e-12 * s)
    error->all(FLERR,
               "Fix {} {}: inertia {} differs from the inertia factor {} of the salt's "
               "discs (fix saltdem/nve ... inertia S, as pair style saltdem/viscous reports it); "
               "drop the keyword, the fix reads S from the integrator",
               style, id, inertia_given, s);
  inertia = s;
  check_finite();

  if (comm->me == 0 && reported != inertia)
    utils::logmesg(lmp,
                   "fix {}: lambda {:.4g}: viscosity model {:.4g}, natural {:.4g} ({})\n"
                   "  driving rate model {:.4g}, natural {:.4g} ({}) = {:.4g} m/ka; length "
                   "{:.4g} ({}), density {:.4g} ({}), inertia x{:.4g} (salt's integrator)\n"
                   "  Reynolds number model {:.3g}, natural {:.3g}; strain rate model {:.3g} 1/s, "
                   "natural {:.3g} 1/s\n"
                   "  1 s of model time is {:.4g} years of natural time\n",
                   style, lambda, eta_model, eta_natural, unit_label("Pa s"), rate, rate / lambda,
                   unit_label("m/s"), natural_rate(), length, unit_label("m"), density,
                   unit_label("kg/m^3"), inertia, reynolds_model(), reynolds_natural(),
                   strain_rate_model(), strain_rate_natural(), lambda / YEAR);
  if (comm->me == 0 && reported != inertia && contrast != 0.0)
    utils::logmesg(lmp,
                   "  buoyancy: density contrast {:.4g} ({}), gravity {:.4g} ({}): stress "
                   "drho g L {:.4g} against the viscous stress eta V/L {:.4g} ({}), ratio {:.4g}\n"
                   "  buoyancy time eta/(|drho| g L) {:.4g} s (model), {:.4g} years (natural); "
                   "buoyancy Reynolds number S rho |drho| g L^3/eta^2 {:.3g}\n",
                   contrast, unit_label("kg/m^3"), gravity, unit_label("m/s^2"), buoyancy_stress(),
                   viscous_stress(), unit_label("Pa"), buoyancy_stress() / viscous_stress(),
                   buoyancy_time(), lambda * buoyancy_time() / YEAR, reynolds_buoyancy());
  reported = inertia;

  const double re = reynolds_model();
  if (re > warn_re && comm->me == 0)
    error->warning(FLERR,
                   "Fix {}: the model Reynolds number {:.3g} (rho S V L / eta) exceeds {:.3g}: "
                   "inertia is no longer negligible, the flow is not the scaled natural flow. "
                   "Lower the rate, the inertia factor or lambda",
                   style, re, warn_re);
}

/* eta_model / (|drho| g L) in s, and S rho |drho| g L^3 / eta_model^2 (0 without contrast) */

double FixSaltdemViscosity::buoyancy_time() const
{
  return (contrast != 0.0) ? eta_model / fabs(buoyancy_stress()) * second : 0.0;
}

double FixSaltdemViscosity::reynolds_buoyancy() const
{
  return (contrast != 0.0) ? density * inertia * fabs(buoyancy_stress()) * length * length /
          (eta_model * eta_model * ftm2v)
                           : 0.0;
}

/* the unit of an input in SI, or the note that it is in the deck's units */

std::string FixSaltdemViscosity::unit_label(const char *si) const
{
  return (strcmp(update->unit_style, "si") == 0) ? si : fmt::format("units {}", update->unit_style);
}

double FixSaltdemViscosity::model_time() const
{
  return update->atime + (update->ntimestep - update->atimestep) * update->dt;
}

/* 1 Re_model (with the inertia factor), 2 Re_natural, 3 model time since
   the fix (s), 4 natural time since the fix (years), 5 natural rate (m/ka),
   6 model strain rate V/L (1/s), 7 natural strain rate (1/s); 8 buoyancy
   stress drho g L, 9 viscous stress eta_model V/L (the deck's pressure units,
   Pa under si), 10 their ratio, 11 buoyancy time eta_model/(|drho| g L) (s),
   12 buoyancy Reynolds number S rho |drho| g L^3 / eta_model^2 (8, 10-12:
   0 without contrast) */

double FixSaltdemViscosity::compute_vector(int n)
{
  switch (n) {
    case 0:
      return reynolds_model();
    case 1:
      return reynolds_natural();
    case 2:
      return (model_time() - t0) * second;
    case 3:
      return lambda * ((model_time() - t0) * second) / YEAR;
    case 4:
      return natural_rate();
    case 5:
      return strain_rate_model();
    case 6:
      return strain_rate_natural();
    case 7:
      return buoyancy_stress();
    case 8:
      return viscous_stress();
    case 9:
      return buoyancy_stress() / viscous_stress();
    case 10:
      return buoyancy_time();
    case 11:
      return reynolds_buoyancy();
  }
  return 0.0;
}

/* the natural clock continues across restarts */

void FixSaltdemViscosity::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    const double list[3] = {SaltDEM::RESTART_MARK, RESTART_VERSION, t0};
    int size = 3 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 3, fp);
  }
}

void FixSaltdemViscosity::restart(char *buf)
{
  double list[3];
  memcpy(list, buf, sizeof(double));
  if (list[0] != SaltDEM::RESTART_MARK)
    error->all(FLERR,
               "Fix {} {}: the restart file was written by another SaltDEM version (its "
               "data of this fix are not marked); continue with the version that wrote it, or "
               "define the fix under another ID to start the natural clock again",
               style, id);
  memcpy(list, buf, sizeof(list));
  if (list[1] != RESTART_VERSION)
    error->all(FLERR,
               "Fix {} {}: the restart file holds this fix's data in layout version {}, "
               "this version reads layout {}",
               style, id, list[1], RESTART_VERSION);
  t0 = list[2];
}
