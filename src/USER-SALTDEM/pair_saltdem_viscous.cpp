/* ----------------------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   pair saltdem/viscous: the linear Newtonian salt, and the no-slip
   boundary contact of cover-salt, salt-wall and cover-wall pairs.  The law
   is SaltDEM::viscous_force (saltdem_contact.h); this file turns the
   requested viscosity into dashpot coefficients and sets the stable dt.
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "modify.h"

#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

static const char RHO_FIX_ID[] = "SALTDEM_VISCOUS_RHO";

PairSaltdemViscous::PairSaltdemViscous(LAMMPS *lmp) :
    PairSaltdem(lmp, "saltdem/viscous", nullptr), params(nullptr), eta(nullptr), vol(nullptr), apress(nullptr), rho(nullptr), index_rho(-1), fluidself(nullptr), isfluid(nullptr), nmax(0),
    any_fluid(false),
    calibration(DEFAULT_CALIBRATION), correction(DEFAULT_CORRECTION), viscfactor(0.5)
{
  comm_forward = 2;
  comm_reverse = 1;
}

PairSaltdemViscous::~PairSaltdemViscous()
{
  if (copymode) return;
  memory->destroy(params);
  memory->destroy(eta);
  memory->destroy(vol);
  memory->destroy(apress);
  memory->destroy(rho);
  memory->destroy(isfluid);
  memory->destroy(fluidself);
  if (modify->get_fix_by_id(RHO_FIX_ID)) modify->delete_fix(RHO_FIX_ID);
}

void PairSaltdemViscous::allocate_params(int n)
{
  memory->create(params, n + 1, n + 1, "pair:params");
  memset(&params[0][0], 0, sizeof(SaltDEM::ViscousParams) * (n + 1) * (n + 1));
  memory->create(eta, n + 1, n + 1, "pair:eta");
  memory->create(isfluid, n + 1, "pair:isfluid");
  memory->create(fluidself, n + 1, "pair:fluidself");
}

void PairSaltdemViscous::compute(int eflag, int vflag)
{
  compute_serial(this, eflag, vflag);
}

/* pair_style saltdem/viscous [correction C] [calibration C] [dtfactor C] [viscfactor C] */

void PairSaltdemViscous::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("pair_style saltdem/viscous {}", arg[iarg]), error);
    const double v = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (strcmp(arg[iarg], "correction") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style saltdem/viscous: correction {} must be > 0", v);
      correction = v;
    } else if (strcmp(arg[iarg], "calibration") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style saltdem/viscous: calibration {} must be > 0", v);
      calibration = v;
    } else if (strcmp(arg[iarg], "dtfactor") == 0) {
      if (v <= 0.0 || v > 0.8)
        error->all(FLERR, "Pair style saltdem/viscous: dtfactor {} must be in (0, 0.8]", v);
      dtfactor = v;
    } else if (strcmp(arg[iarg], "viscfactor") == 0) {
      if (v <= 0.0 || v > 1.0)
        error->all(FLERR, "Pair style saltdem/viscous: viscfactor {} must be in (0, 1]", v);
      viscfactor = v;
    } else
      error->all(FLERR,
                 "Pair style saltdem/viscous: unknown keyword '{}' (expected: correction, calibration, "
                 "dtfactor, viscfactor)",
                 arg[iarg]);
    iarg += 2;
  }
}

/* pair_coeff I J eta kn fluid h
   pair_coeff I J eta kn contact gap [tangential ratio] */

void PairSaltdemViscous::coeff(int narg, char **arg)
{
  const char *usage =
      "pair_coeff I J eta kn fluid h K  or  pair_coeff I J eta kn contact gap [tangential R]";
  int ilo, ihi, jlo, jhi;
  check_types(narg, arg, 6, usage, ilo, ihi, jlo, jhi);

  SaltDEM::ViscousParams p{};
  p.eta = utils::numeric(FLERR, arg[2], false, lmp);
  p.kn = utils::numeric(FLERR, arg[3], false, lmp);
  if (p.eta <= 0.0) error->all(FLERR, "Pair style saltdem/viscous: eta = {} must be > 0", p.eta);
  if (p.kn < 0.0) error->all(FLERR, "Pair style saltdem/viscous: kn = {} must be >= 0", p.kn);
  p.ratio = 1.0;

  std::string kw = arg[4];
  std::string opt;
  if (kw == "fluid") {
    p.mode = SaltDEM::VISCOUS_FLUID;
    p.h = utils::numeric(FLERR, arg[5], false, lmp);
    if (p.h <= 0.0) error->all(FLERR, "Pair style saltdem/viscous: fluid h = {} must be > 0", p.h);
    if (narg != 7)
      error->all(FLERR, "Pair style saltdem/viscous: 'fluid' takes h and K, got {} values; usage: {}",
                 narg - 5, usage);
    p.K = utils::numeric(FLERR, arg[6], false, lmp);
    if (p.K < 0.0) error->all(FLERR, "Pair style saltdem/viscous: fluid K = {} must be >= 0", p.K);
  } else if (kw == "contact") {
    p.mode = SaltDEM::VISCOUS_CONTACT;
    if (p.kn <= 0.0)
      error->all(FLERR, "Pair style saltdem/viscous: contact kn = {} must be > 0 (a boundary needs "
                 "its elastic repulsion)", p.kn);
    p.gap = utils::numeric(FLERR, arg[5], false, lmp);
    if (p.gap < 0.0) error->all(FLERR, "Pair style saltdem/viscous: contact gap = {} must be >= 0", p.gap);
    if (narg == 8 && strcmp(arg[6], "tangential") == 0) {
      p.ratio = utils::numeric(FLERR, arg[7], false, lmp);
      if (p.ratio < 0.0)
        error->all(FLERR, "Pair style saltdem/viscous: tangential ratio = {} must be >= 0", p.ratio);
    } else if (narg != 6)
      error->all(FLERR, "Pair style saltdem/viscous: unexpected arguments after 'contact {}' "
                 "(allowed: tangential R); usage: {}", arg[5], usage);
  } else
    error->all(FLERR, "Pair style saltdem/viscous: unknown law '{}' (expected fluid or contact); usage: {}",
               kw, usage);

  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      params[i][j] = p;
      eta[i][j] = p.eta;
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients" + utils::errorurl(21));
}

/* cross types of the same law: springs and dashpots in series, lengths
   averaged; two different laws do not mix (set the pair explicitly) */

void PairSaltdemViscous::mix(int i, int j)
{
  auto series = [](double x, double y) { return (x + y > 0.0) ? 2.0 * x * y / (x + y) : 0.0; };
  const auto &a = params[i][i];
  const auto &b = params[j][j];
  if (a.mode != b.mode)
    error->all(FLERR,
               "Pair style saltdem/viscous: types {} ({}) and {} ({}) use different laws and cannot "
               "be mixed; add 'pair_coeff {} {} ...' (contact for a boundary)",
               i, a.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", j,
               b.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", i, j);
  auto &p = params[i][j];
  p = a;
  p.eta = series(eta[i][i], eta[j][j]);
  p.kn = series(a.kn, b.kn);
  p.h = 0.5 * (a.h + b.h);
  p.K = sqrt(a.K * b.K);
  p.rho0 = 0.0;
  p.ratio = 0.5 * (a.ratio + b.ratio);
  p.gap = 0.5 * (a.gap + b.gap);
  eta[i][j] = p.eta;
}

void PairSaltdemViscous::init_style()
{
  dim2 = (domain->dimension == 2);
  volfac = dim2 ? M_PI : 4.0 * M_PI / 3.0;
  any_fluid = false;
  for (int i = 1; i <= atom->ntypes; i++) {
    // (under pair hybrid, types of other sub-styles have no coefficients here)
    fluidself[i] = (setflag[i][i] && params[i][i].mode == SaltDEM::VISCOUS_FLUID) ? 1 : 0;
    isfluid[i] = (fluidself[i] && params[i][i].K > 0.0) ? 1 : 0;
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && params[i][j].mode == SaltDEM::VISCOUS_FLUID) any_fluid = true;
  }
  // the continuity density of fluid particles lives with the atoms
  if (any_fluid) {
    if (!modify->get_fix_by_id(RHO_FIX_ID))
      modify->add_fix(fmt::format("{} all property/atom d_saltdem_rho writedata no", RHO_FIX_ID));
    int flag, cols;
    index_rho = atom->find_custom("saltdem_rho", flag, cols);
    if (index_rho < 0 || flag != 1 || cols != 0)
      error->all(FLERR, "Pair style saltdem/viscous: per-atom property d_saltdem_rho is missing");
  }
  PairSaltdem::init_style();
}

/* rho[i] += m_j q(i, j), rho[j] += m_i q(i, j) over the FLUID pairs of the
   list (q symmetric under i <-> j), summed onto the owners with newton on */

template <class Q> void PairSaltdemViscous::sum_fluid_pairs(Q &&q)
{
  double **x = atom->x;
  double *m = atom->rmass;
  int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const auto &p = params[type[i]][type[j]];
      if (p.mode != SaltDEM::VISCOUS_FLUID) continue;
      const double d[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      const double w = q(i, j, p, d);
      rho[i] += m[j] * w;
      if (newton_pair || j < nlocal) rho[j] += m[i] * w;
    }
  }
  if (newton_pair) comm->reverse_comm(this);
}

/* FLUID density, volume and pressure.  The density of a fluid particle is
   carried per atom (fix property/atom d_saltdem_rho, so it migrates and
   restarts with the atom) and follows the continuity equation
     d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
   over the FLUID pairs (walls and cover included: moving boundaries compress
   the fluid).  It starts at the reference rho0 of its type, the mean kernel
   density sum_j m_j W_ij of that type at the first step, so the fluid starts
   free of pressure.  A summed kernel density would instead drift upwards as
   particles pair up (the mean of sum_j W grows while the volume does not).
   Then the volume m / rho, the pressure P = K (rho / rho0 - 1) and
   a = m P / rho^2, sent to the ghosts. */

void PairSaltdemViscous::pre_loop()
{
  if (!any_fluid) return;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  if (atom->nmax > nmax) {
    memory->destroy(vol);
    memory->destroy(apress);
    memory->destroy(rho);
    nmax = atom->nmax;
    memory->create(vol, nmax, "pair:vol");
    memory->create(apress, nmax, "pair:apress");
    memory->create(rho, nmax, "pair:rho");
  }
  double **v = atom->v;
  double *m = atom->rmass;
  int *type = atom->type;
  double *rhoc = atom->dvector[index_rho];
  const int dim = domain->dimension;
  const int nt = atom->ntypes;

  // reference density of each fluid type, once: mean kernel density
  bool need = false;
  for (int t = 1; t <= nt; t++)
    if (fluidself[t] && params[t][t].rho0 <= 0.0) need = true;
  if (need) {
    for (int i = 0; i < nall; i++) {
      const int t = type[i];
      rho[i] = (i < nlocal && fluidself[t]) ? m[i] * SaltDEM::wendland_c2(dim, params[t][t].h, 0.0) : 0.0;
    }
    sum_fluid_pairs([&](int, int, const SaltDEM::ViscousParams &p, const double *d) {
      return SaltDEM::wendland_c2(dim, p.h, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    });
    std::vector<double> sum(2 * (nt + 1), 0.0), all(2 * (nt + 1));
    for (int i = 0; i < nlocal; i++) {
      sum[2 * type[i]] += rho[i];
      sum[2 * type[i] + 1] += 1.0;
    }
    MPI_Allreduce(sum.data(), all.data(), 2 * (nt + 1), MPI_DOUBLE, MPI_SUM, world);
    for (int t = 1; t <= nt; t++)
      if (fluidself[t] && params[t][t].rho0 <= 0.0 && all[2 * t + 1] > 0.0) {
        params[t][t].rho0 = all[2 * t] / all[2 * t + 1];
        if (comm->me == 0)
          utils::logmesg(lmp, "pair saltdem/viscous: reference density of fluid type {} = {:.15g}\n",
                         t, params[t][t].rho0);
      }
  }
  for (int i = 0; i < nlocal; i++)
    if (fluidself[type[i]] && rhoc[i] <= 0.0) rhoc[i] = params[type[i]][type[i]].rho0;

  // continuity (not during setup, like the history of the contact styles)
  if (!update->setupflag) {
    for (int i = 0; i < nall; i++) rho[i] = 0.0;
    sum_fluid_pairs([&](int i, int j, const SaltDEM::ViscousParams &p, const double *d) {
      const double s = 1.0 - 0.5 * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / p.h;
      if (s <= 0.0) return 0.0;
      // v_ij . grad_i W_ij, with grad_i W = -cw (1 - r/2h)^3 (x_i - x_j)
      return -p.cw * s * s * s *
          ((v[i][0] - v[j][0]) * d[0] + (v[i][1] - v[j][1]) * d[1] + (v[i][2] - v[j][2]) * d[2]);
    });
    const double dt = update->dt;
    for (int i = 0; i < nlocal; i++)
      if (fluidself[type[i]]) rhoc[i] += dt * rho[i];
  }

  // a boundary particle (wall, cover) gets the volume it would have at the
  // fluid's reference density
  double rhob = 0.0;
  for (int t = 1; t <= nt; t++)
    if (fluidself[t]) rhob = MAX(rhob, params[t][t].rho0);
  for (int i = 0; i < nlocal; i++) {
    const auto &p = params[type[i]][type[i]];
    const double r = fluidself[type[i]] ? rhoc[i] : rhob;
    vol[i] = (r > 0.0) ? m[i] / r : 0.0;
    apress[i] = (isfluid[type[i]] && p.rho0 > 0.0) ? m[i] * p.K * (r / p.rho0 - 1.0) / (r * r) : 0.0;
  }
  comm->forward_comm(this);
}

int PairSaltdemViscous::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  int k = 0;
  for (int i = 0; i < n; i++) {
    buf[k++] = vol[list[i]];
    buf[k++] = apress[list[i]];
  }
  return k;
}

void PairSaltdemViscous::unpack_forward_comm(int n, int first, double *buf)
{
  int k = 0;
  for (int i = first; i < first + n; i++) {
    vol[i] = buf[k++];
    apress[i] = buf[k++];
  }
}

int PairSaltdemViscous::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = rho[first + i];
  return n;
}

void PairSaltdemViscous::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int i = 0; i < n; i++) rho[list[i]] += buf[i];
}

double PairSaltdemViscous::memory_usage()
{
  return PairSaltdem::memory_usage() + 3.0 * nmax * sizeof(double);
}

/* the viscosity may have been changed through extract("eta") since the
   last run (fix adapt, fix saltdem/viscosity): derive the dashpots here */

double PairSaltdemViscous::init_one(int i, int j)
{
  if (setflag[i][j]) params[i][j].eta = eta[i][j];
  const double cut = PairSaltdem::init_one(i, j);
  auto &p = params[i][j];
  p.cw = SaltDEM::wendland_c2_grad_over_r(domain->dimension, p.h > 0.0 ? p.h : 1.0);
  p.kfac = 2.0 * correction * p.eta * p.cw;
  p.gn = calibration * p.eta;
  p.gt = p.ratio * p.gn;
  params[j][i] = p;
  eta[j][i] = eta[i][j] = p.eta;
  return cut;
}

/* Limits per type pair.  Elastic: dtfactor * sqrt(m/kn).  Viscous: an
   explicit dashpot network is stable while dt < m / sum(gamma) for every
   particle (Gershgorin).  FLUID: the kernel sums to sum(gamma) = 7 eta V / h^2
   (2D and 3D), so dt < S m h^2 / (7 eta V).
   CONTACT: a disc's tangential dashpot also spins it (1/m + l^2/I = 3/m, 3.5/m
   for a sphere), so dt < m / (g (1 + rot ratio)).  Both times viscfactor. */

double PairSaltdemViscous::stable_dt(const double *mmin, std::string &why)
{
  const int n = atom->ntypes;
  // smallest inertial mass per unit disc volume per type
  std::vector<double> local(n + 1, DBL_MAX), mv(n + 1);
  for (int i = 0; i < atom->nlocal; i++) {
    const double s = inertia_scale(i);
    const double r = atom->radius[i];
    const double vol = volfac * (dim2 ? r * r : r * r * r);
    if (s > 0.0 && vol > 0.0) local[atom->type[i]] = MIN(local[atom->type[i]], s * atom->rmass[i] / vol);
  }
  MPI_Allreduce(&local[1], &mv[1], n, MPI_DOUBLE, MPI_MIN, world);

  const double rot = dim2 ? 3.0 : 3.5;
  double best = DBL_MAX;
  auto consider = [&](double lim, std::string &&reason) {
    if (lim < best) {
      best = lim;
      why = reason;
    }
  };
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (!setflag[i][j]) {
        if (!setflag[i][i] || !setflag[j][j]) continue;    // another hybrid sub-style's pair
        mix(i, j);                                          // init_one() has not run yet
      }
      if (mmin[i] < 0.0 || mmin[j] < 0.0) continue;               // a type without atoms
      if (mmin[i] == DBL_MAX && mmin[j] == DBL_MAX) continue;    // walls only
      const double m = MIN(mmin[i], mmin[j]);
      const double e = eta[i][j];
      const auto &p = params[i][j];
      if (p.kn > 0.0)
        consider(dtfactor * sqrt(m / p.kn),
               fmt::format("kn = {:.6g} of types {} {} with the lightest mass {:.6g} "
                           "(dt < {} * sqrt(m/kn))", p.kn, i, j, m, dtfactor));
      double lim;
      std::string formula;
      if (p.mode == SaltDEM::VISCOUS_FLUID) {
        // V = 1/sum W is not known before the first step: bound it by the
        // disc volume over a packing fraction of 0.7
        lim = viscfactor * MIN(mv[i], mv[j]) * 0.7 * p.h * p.h / (7.0 * correction * e);
        formula = fmt::format("dt < {} * S m h^2 / (7 eta V), V = disc/0.7, h = {:.6g}", viscfactor, p.h);
        // sound: c^2 = K / rho with the inertial density, CFL 0.25 h / c
        if (p.K > 0.0) {
          const double c = sqrt(p.K / (0.7 * MIN(mv[i], mv[j])));
          consider(0.25 * p.h / c,
                   fmt::format("K = {:.6g} of types {} {} (sound speed {:.4g} with the inertial "
                               "density; dt < 0.25 h / c, h = {:.6g}); a larger dt needs a smaller "
                               "K or more inertia", p.K, i, j, c, p.h));
        }
      } else {
        lim = viscfactor * m / (calibration * e * (1.0 + rot * p.ratio));
        formula = fmt::format("dt < {} * S m / (calibration * eta * (1 + {} * ratio))", viscfactor, rot);
      }
      consider(lim, fmt::format("eta = {:.6g} of types {} {} ({}); a larger dt needs a smaller eta "
                                "or more inertia for the viscous discs ('fix saltdem/nve ... inertia "
                                "S' with S >= {:.3g} times the present one)",
                                e, i, j, formula, update->dt / lim));
    }
  return best == DBL_MAX ? 0.0 : best;
}

/* ---------------------------------------------------------------------- */

void PairSaltdemViscous::read_restart(FILE *fp)
{
  PairSaltdem::read_restart(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j]) eta[i][j] = params[i][j].eta;
}

void PairSaltdemViscous::write_restart_settings(FILE *fp)
{
  fwrite(&calibration, sizeof(double), 1, fp);
  fwrite(&correction, sizeof(double), 1, fp);
  fwrite(&dtfactor, sizeof(double), 1, fp);
  fwrite(&viscfactor, sizeof(double), 1, fp);
}

void PairSaltdemViscous::read_restart_settings(FILE *fp)
{
  double buf[4];
  if (comm->me == 0) utils::sfread(FLERR, buf, sizeof(double), 4, fp, nullptr, error);
  MPI_Bcast(buf, 4, MPI_DOUBLE, 0, world);
  calibration = buf[0];
  correction = buf[1];
  dtfactor = buf[2];
  viscfactor = buf[3];
}

/* "eta": per type pair viscosity (dim 2), read and changed by fix adapt and
   fix saltdem/viscosity; "calibration": dashpot per unit viscosity */

void *PairSaltdemViscous::extract(const char *str, int &dim)
{
  if (strcmp(str, "eta") == 0) {
    dim = 2;
    return (void *) eta;
  }
  dim = 0;
  if (strcmp(str, "calibration") == 0) return (void *) &calibration;
  return nullptr;
}
