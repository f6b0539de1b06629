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

   pair saltdem/viscous: the linear Newtonian salt, and the no-slip
   boundary contact of cover-salt, salt-wall and cover-wall pairs.  The laws
   are SaltDEM::viscous_fluid_force and viscous_contact_force
   (saltdem_contact_viscous.h); this file turns the requested viscosity into dashpot
   coefficients, carries the fluid's density and sets the stable dt.
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous.h"

#include "fix_saltdem_density.h"
#include "saltdem_check.h"
#include "saltdem_contact_viscous.h"
#include "saltdem_pair_loop.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

// what the pair's forward and reverse communication carries
enum { COMM_PRESSURE, COMM_SUBSTEP };

PairSaltdemViscous::PairSaltdemViscous(LAMMPS *lmp) :
    PairSaltdem(lmp, "saltdem/viscous", nullptr), params(nullptr), eta(nullptr), vol(nullptr),
    pmat(nullptr), moment(nullptr), fill(nullptr), mdens(nullptr), scratch(nullptr),
    fix_density(nullptr), fluidself(nullptr), isfluid(nullptr), nmax(0), any_fluid(false),
    calibration(DEFAULT_CALIBRATION), correction(DEFAULT_CORRECTION), viscfactor(0.8),
    fill_max(DEFAULT_FILL_MAX), substeps(1), noslip_surface(false), slip(nullptr), usub(nullptr),
    fsub(nullptr), ksub(nullptr), fother(nullptr), comm_mode(COMM_PRESSURE),
    calibration_checked(DEFAULT_CALIBRATION), salt_inertia(1.0)
{
  // volume, boundary fill, pressure matrix and no-slip offset, or the sub-step velocities; the
  // kernel sums of ghosts (newton on), or their sub-step forces
  comm_forward = 2 + SaltDEM::NSYM + 3;
  comm_reverse = NMOM_MAX;
}

PairSaltdemViscous::~PairSaltdemViscous()
{
  if (copymode) return;
  memory->destroy(params);
  memory->destroy(eta);
  memory->destroy(vol);
  memory->destroy(pmat);
  memory->destroy(moment);
  memory->destroy(fill);
  memory->destroy(mdens);
  memory->destroy(scratch);
  memory->destroy(slip);
  memory->destroy(usub);
  memory->destroy(fsub);
  memory->destroy(ksub);
  memory->destroy(fother);
  memory->destroy(isfluid);
  memory->destroy(fluidself);
  // the salt's density is this pair style's state: it goes with it
  if (!density_id.empty() && modify->get_fix_by_id(density_id)) modify->delete_fix(density_id);
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

void PairSaltdemViscous::apply_substeps()
{
  if (substeps < 2 || !any_fluid) return;
  if (domain->dimension == 2)
    viscous_substeps<2>();
  else
    viscous_substeps<3>();
}

void *PairSaltdemViscous::pair_params(int i, int j)
{
  return &params[i][j];
}

size_t PairSaltdemViscous::params_size() const
{
  return sizeof(SaltDEM::ViscousParams);
}

/* the dashpots of a CONTACT pair act up to its gap beyond contact; a FLUID pair reaches 2h
   between the centres */

double PairSaltdemViscous::range(int i, int j) const
{
  return params[i][j].mode == SaltDEM::VISCOUS_CONTACT ? params[i][j].gap : 0.0;
}

double PairSaltdemViscous::range_abs(int i, int j) const
{
  return params[i][j].mode == SaltDEM::VISCOUS_FLUID ? 2.0 * params[i][j].h : 0.0;
}

double PairSaltdemViscous::fluid_h(int t) const
{
  return params[t][t].h;
}

double PairSaltdemViscous::fluid_K(int t) const
{
  return params[t][t].K;
}

/* pair_style saltdem/viscous [correction C] [calibration C] [dtfactor C] [viscfactor C]
   [fill F] [substeps N] [noslip centre|surface] */

void PairSaltdemViscous::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("pair_style {} {}", name, arg[iarg]), error);
    if (strcmp(arg[iarg], "substeps") == 0) {
      substeps = parse_substeps(arg[iarg + 1]);
      iarg += 2;
      continue;
    }
    if (strcmp(arg[iarg], "noslip") == 0) {
      if (strcmp(arg[iarg + 1], "surface") == 0)
        noslip_surface = true;
      else if (strcmp(arg[iarg + 1], "centre") == 0 || strcmp(arg[iarg + 1], "center") == 0)
        noslip_surface = false;
      else
        error->all(FLERR,
                   "Pair style {}: noslip '{}' is not a boundary (expected surface: the fluid "
                   "meets a boundary disc at its surface, or centre: at its centre)",
                   name, arg[iarg + 1]);
      iarg += 2;
      continue;
    }
    const double v = SaltDEM::numeric(FLERR, arg[iarg + 1],
                                      fmt::format("Pair style {}: {}", name, arg[iarg]), lmp);
    if (strcmp(arg[iarg], "correction") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style {}: correction {} must be > 0", name, v);
      correction = v;
    } else if (strcmp(arg[iarg], "calibration") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style {}: calibration {} must be > 0", name, v);
      calibration = v;
    } else if (strcmp(arg[iarg], "dtfactor") == 0) {
      if (v <= 0.0 || v > DTFACTOR_MAX)
        error->all(FLERR, "Pair style {}: dtfactor {} must be in (0, {}]", name, v, DTFACTOR_MAX);
      dtfactor = v;
    } else if (strcmp(arg[iarg], "viscfactor") == 0) {
      if (v <= 0.0 || v > 1.0)
        error->all(FLERR, "Pair style {}: viscfactor {} must be in (0, 1]", name, v);
      viscfactor = v;
    } else if (strcmp(arg[iarg], "fill") == 0) {
      if (v < 1.0 || v > 100.0)
        error->all(FLERR,
                   "Pair style {}: fill {} must be in [1, 100] (the most a boundary particle "
                   "stands for, in its own volumes; 1: none)",
                   name, v);
      fill_max = v;
    } else
      error->all(FLERR,
                 "Pair style {}: unknown keyword '{}' (expected: correction, calibration, "
                 "dtfactor, viscfactor, fill, substeps, noslip)",
                 name, arg[iarg]);
    iarg += 2;
  }
}

int PairSaltdemViscous::parse_substeps(const char *str)
{
  const int n = utils::inumeric(FLERR, str, false, lmp);
  if (n < 1 || n > MAX_SUBSTEPS)
    error->all(FLERR,
               "Pair style {}: substeps {} must be in [1, {}] (1: the viscosity in the force pass)",
               name, n, MAX_SUBSTEPS);
  return n;
}

/* saltdem/timestep F substeps N: the sub-steps of a style read from a restart file too */

bool PairSaltdemViscous::set_substeps(int n)
{
  substeps = parse_substeps(std::to_string(n).c_str());
  return true;
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
  auto value = [&](const char *str, const char *what) {
    return SaltDEM::numeric(FLERR, str, fmt::format("Pair style {}: {}", name, what), lmp);
  };
  const double eta_given = value(arg[2], "eta");
  p.kn = value(arg[3], "kn");
  if (eta_given <= 0.0) error->all(FLERR, "Pair style {}: eta = {} must be > 0", name, eta_given);
  if (p.kn < 0.0) error->all(FLERR, "Pair style {}: kn = {} must be >= 0", name, p.kn);
  p.ratio = 1.0;

  std::string kw = arg[4];
  if (kw == "fluid") {
    p.mode = SaltDEM::VISCOUS_FLUID;
    p.h = value(arg[5], "fluid h");
    if (p.h <= 0.0) error->all(FLERR, "Pair style {}: fluid h = {} must be > 0", name, p.h);
    if (narg != 7)
      error->all(FLERR, "Pair style {}: 'fluid' takes h and K, got {} values; usage: {}", name,
                 narg - 5, usage);
    p.K = value(arg[6], "fluid K");
    if (p.K < 0.0) error->all(FLERR, "Pair style {}: fluid K = {} must be >= 0", name, p.K);
  } else if (kw == "contact") {
    p.mode = SaltDEM::VISCOUS_CONTACT;
    if (p.kn <= 0.0)
      error->all(FLERR,
                 "Pair style {}: contact kn = {} must be > 0 (a boundary needs its elastic "
                 "repulsion)",
                 name, p.kn);
    p.gap = value(arg[5], "contact gap");
    if (p.gap < 0.0) error->all(FLERR, "Pair style {}: contact gap = {} must be >= 0", name, p.gap);
    if (narg == 8 && strcmp(arg[6], "tangential") == 0) {
      p.ratio = value(arg[7], "tangential ratio");
      if (p.ratio < 0.0)
        error->all(FLERR, "Pair style {}: tangential ratio = {} must be >= 0", name, p.ratio);
    } else if (narg != 6)
      error->all(FLERR,
                 "Pair style {}: unexpected arguments after 'contact {}' (allowed: "
                 "tangential R); usage: {}",
                 name, arg[5], usage);
  } else
    error->all(FLERR, "Pair style {}: unknown law '{}' (expected fluid or contact); usage: {}",
               name, kw, usage);

  assign_coeffs(ilo, ihi, jlo, jhi, [&](int i, int j) {
    params[i][j] = p;
    eta[i][j] = eta_given;
  });
}

/* cross types of the same law: springs and dashpots in series, lengths
   averaged; two different laws do not mix (set the pair explicitly) */

void PairSaltdemViscous::mix(int i, int j)
{
  const auto &a = params[i][i];
  const auto &b = params[j][j];
  if (a.mode != b.mode)
    error->all(FLERR,
               "Pair style {}: types {} ({}) and {} ({}) use different laws and cannot be mixed; "
               "add 'pair_coeff {} {} ...' (contact for a boundary)",
               name, i, a.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", j,
               b.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", i, j);
  auto &p = params[i][j];
  p = a;
  eta[i][j] = mix_series(eta[i][i], eta[j][j]);
  p.kn = mix_series(a.kn, b.kn);
  p.h = 0.5 * (a.h + b.h);
  p.K = sqrt(a.K * b.K);
  p.ratio = 0.5 * (a.ratio + b.ratio);
  p.gap = 0.5 * (a.gap + b.gap);
}

void PairSaltdemViscous::init_style()
{
  any_fluid = false;
  influid.assign(atom->ntypes + 1, 0);
  for (int i = 1; i <= atom->ntypes; i++) {
    // (under pair hybrid, types of other sub-styles have no coefficients here)
    fluidself[i] = (setflag[i][i] && params[i][i].mode == SaltDEM::VISCOUS_FLUID) ? 1 : 0;
    isfluid[i] = (fluidself[i] && params[i][i].K > 0.0) ? 1 : 0;
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && params[i][j].mode == SaltDEM::VISCOUS_FLUID)
        any_fluid = influid[i] = influid[j] = 1;
  }
  // the continuity density of the fluid particles is the state of an internal fix
  // (FixSaltdemDensity), created here so that it finds its data in a restart file.  Its ID:
  // SALTDEM_DENSITY, or SALTDEM_DENSITY_N for the N-th saltdem/viscous sub-style of pair
  // hybrid (N > 1), the same for the same deck after read_restart
  fix_density = nullptr;
  if (any_fluid) {
    const auto subs = substyles();
    const int nth = 1 + (int) (std::find(subs.begin(), subs.end(), this) - subs.begin());
    density_id = (nth == 1) ? "SALTDEM_DENSITY" : fmt::format("SALTDEM_DENSITY_{}", nth);
    Fix *f = modify->get_fix_by_id(density_id);
    if (!f) f = modify->add_fix(fmt::format("{} all SALTDEM_DENSITY", density_id));
    fix_density = dynamic_cast<FixSaltdemDensity *>(f);
    if (!fix_density)
      error->all(FLERR,
                 "Pair style {}: fix ID {} is taken by a fix of style {}; the pair style "
                 "keeps the salt's density in an internal fix of that ID",
                 name, density_id, f->style);
    fix_density->pair = this;
  }
  // the sub-steps move the atoms that a fix integrates, with the inertia it gives them
  integrators = find_integrators();
  // (here, where every rank takes part: extract() may be called by one rank alone)
  salt_inertia = find_salt_inertia();
  if (any_fluid && noslip_surface && comm->me == 0)
    utils::logmesg(lmp,
                   "Pair style {}: no-slip at the surfaces of the boundary discs (noslip "
                   "surface: the fluid's velocity extrapolated into them)\n",
                   name);
  // said at every run: a resumed run keeps the file's sub-steps unless they are set again
  if (any_fluid && substeps > 1 && comm->me == 0)
    utils::logmesg(lmp, "Pair style {}: the viscosity in {} sub-steps per step (substeps)\n", name,
                   substeps);
  PairSaltdem::init_style();
}

/* the kernel density out[i] = sum_j mu_ij W_ij (j = i included) of every owned atom of a type
   whose own pair is FLUID, over the FLUID pairs of the list, owned and ghost atoms, and
   whether its kernel is full (interior[i] = 1: its neighbours surround it, see
   SaltDEM::INTERIOR_MAX; 0 otherwise): for the reference density (FixSaltdemDensity).  The
   sums use the moment array (the density in the slot WF, the first moment in the slots of
   the fluid moment, its norm in WB; Layout) */

void PairSaltdemViscous::kernel_density(double *out, double *interior)
{
  grow_arrays();
  material_density();
  if (domain->dimension == 2)
    kernel_density<2>(out, interior);
  else
    kernel_density<3>(out, interior);
}

template <int DIM> void PairSaltdemViscous::kernel_density(double *out, double *interior)
{
  const auto x = atom->x ? (const double(*)[3]) atom->x[0] : nullptr;    // (none on an empty rank)
  const double *m = atom->rmass;
  const double *radius = atom->radius;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  using L = Layout<DIM>;
  std::fill_n(moment, L::NMOM * nall, 0.0);
  for (int i = 0; i < nlocal; i++) {
    const int t = type[i];
    if (fluidself[t])
      moment[L::NMOM * i + L::WF] = m[i] * SaltDEM::wendland_c2(DIM, params[t][t].h, 0.0);
  }
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    const SaltDEM::ViscousParams *prow = params[type[i]];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const SaltDEM::ViscousParams &p = prow[type[j]];
      if (p.mode != SaltDEM::VISCOUS_FLUID) continue;
      double d[3] = {0.0, 0.0, 0.0}, rsq = 0.0;
      for (int k = 0; k < DIM; k++) {
        d[k] = x[i][k] - x[j][k];
        rsq += d[k] * d[k];
      }
      const double r = sqrt(rsq);
      const double w = SaltDEM::wendland_c2(DIM, p.h, r);
      const double s = (r < 2.0 * p.h) ? 1.0 - 0.5 * r / p.h : 0.0;
      const double g = s * s * s;    // |W'|/r up to a constant
      const double mij = partner_mass<DIM>(radius, i, j), mji = partner_mass<DIM>(radius, j, i);
      double *Mi = &moment[L::NMOM * i];
      Mi[L::WF] += mij * w;
      Mi[L::WB] += mij * g * r;
      for (int k = 0; k < DIM; k++) Mi[k] += mij * g * d[k];
      if (newton_pair || j < nlocal) {
        double *Mj = &moment[L::NMOM * j];
        Mj[L::WF] += mji * w;
        Mj[L::WB] += mji * g * r;
        for (int k = 0; k < DIM; k++) Mj[k] -= mji * g * d[k];
      }
    }
  }
  comm_mode = COMM_PRESSURE;
  if (newton_pair) comm->reverse_comm(this);
  for (int i = 0; i < nlocal; i++) {
    const double *Mi = &moment[L::NMOM * i];
    const int t = type[i];
    out[i] = fluidself[t] ? Mi[L::WF] : 0.0;
    double g2 = 0.0;
    for (int k = 0; k < DIM; k++) g2 += Mi[k] * Mi[k];
    interior[i] = (fluidself[t] && Mi[L::WB] > 0.0 && sqrt(g2) < SaltDEM::INTERIOR_MAX * Mi[L::WB])
        ? 1.0
        : 0.0;
  }
}

/* FLUID volume and pressure.  The density of a fluid particle is the state of the internal
   fix FixSaltdemDensity (it migrates and restarts with the atom) and follows the continuity
   equation
     d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
   over the FLUID pairs (walls and cover included: moving boundaries compress the fluid),
   summed in the force pass into the fix's d rho / dt and integrated by the fix after it, as
   LAMMPS's SPH styles do: the pressure of a step is that of the density at the end of the
   step before.  It starts at the reference rho0 of its type, the mean kernel density
   sum_j m_j W_ij of the particles of that type whose kernel is full (away from free surfaces
   and boundaries) at the setup of the first run (the fix measures it), so the fluid starts
   free of pressure.  A summed kernel density would instead drift upwards as particles pair up
   (the mean of sum_j W grows while the volume does not).  Here, before the force pass: the
   kernel sums of the present positions (kernel_moments), each fluid particle's boundary fill
   (SaltDEM::boundary_fill), its volume m / rho and its pressure matrix A = m P / rho^2 L with
   the equation of state and the kernel-gradient correction L, whose moment counts the
   boundary partners with the fill (SaltDEM::particle_volume, pressure_term, pressure_matrix),
   sent to the ghosts. */

void PairSaltdemViscous::pre_loop()
{
  grow_arrays();
  if (!any_fluid) return;
  material_density();
  if (domain->dimension == 2)
    pressure_matrices<2>();
  else
    pressure_matrices<3>();
  comm_mode = COMM_PRESSURE;
  comm->forward_comm(this);
}

template <int DIM> void PairSaltdemViscous::pressure_matrices()
{
  using L = Layout<DIM>;
  const int nlocal = atom->nlocal;
  const double *m = atom->rmass;
  const int *type = atom->type;
  const double *rho = fix_density->rho;
  const double *rho0 = fix_density->rho0.data();
  const int nt = atom->ntypes;

  kernel_moments<DIM>();
  if (noslip_surface) noslip_offsets<DIM>();

  // a boundary particle (wall, cover) has, beside a fluid particle, the volume of the fluid it
  // stands for (pair_weights: its mass as that fluid's over the fluid's reference density);
  // between boundary particles, its own at the densest fluid's reference density.  A fluid
  // particle created during the run starts at its reference density
  double rhob = 0.0;
  irho0.assign(nt + 1, 0.0);
  for (int t = 1; t <= nt; t++)
    if (fluidself[t] && rho0[t] > 0.0) {
      rhob = MAX(rhob, rho0[t]);
      irho0[t] = 1.0 / rho0[t];
    }
  for (int i = 0; i < nlocal; i++) {
    const int t = type[i];
    const double r = fluidself[t] ? (rho[i] > 0.0 ? rho[i] : rho0[t]) : rhob;
    vol[i] = SaltDEM::particle_volume(m[i], r);
    const double *M = &moment[L::NMOM * i];
    fill[i] = fluidself[t] ? SaltDEM::boundary_fill(M[L::WF], M[L::WB], r, rho0[t], fill_max) : 1.0;
    double *A = &pmat[L::NS * i];
    if (isfluid[t]) {
      const double a = SaltDEM::pressure_term(m[i], params[t][t].K, r, rho0[t]);
      for (int k = 0; k < L::NS; k++) A[k] = M[k] + fill[i] * M[L::NS + k];
      SaltDEM::pressure_matrix<DIM>(a, r, A);
    } else
      for (int k = 0; k < L::NS; k++) A[k] = 0.0;
  }
}

/* the kernel sums of the owned particles of the types whose own pair is FLUID, over the FLUID
   pairs of the list, split into their fluid and their boundary partners (a partner whose own
   pair is not FLUID): the moments S = sum_j m_j w_ij d_ij d_ij and the kernel sums
   sum_j m_j W_ij (i itself among the fluid's); with noslip surface, in the same slots of a
   boundary particle b (whose own sums are not needed), its fluid partners' kernel sums
   sum_f m_f W_bf in WF, sum_f m_f W_bf (x_f - x_b) in slots 0.. and sum_f m_f W_bf v_f in
   slots NS.. (Layout; noslip_offsets); with newton on the ghosts' parts go home; with viscous
   sub-steps also the list of the FLUID pairs within 2h and their kernel factors */

template <int DIM> void PairSaltdemViscous::kernel_moments()
{
  using L = Layout<DIM>;
  constexpr int NS = L::NS;
  const auto x = atom->x ? (const double(*)[3]) atom->x[0] : nullptr;    // (none on an empty rank)
  const auto v = atom->v ? (const double(*)[3]) atom->v[0] : nullptr;
  const double *m = atom->rmass;
  const double *radius = atom->radius;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  // (a loop over the member pointer would store one double at a time)
  std::fill_n(moment, L::NMOM * (newton_pair ? nall : nlocal), 0.0);
  const bool sub = substeps > 1;
  const bool ext = noslip_surface;
  // a boundary particle b's sums of a fluid partner f at d = x_f - x_b (sign: +1) or x_b - x_f
  auto add_fluid = [&](double *Mb, int f, double mw, const double *d, double sign) {
    Mb[L::WF] += mw;
    for (int k = 0; k < DIM; k++) {
      Mb[k] += sign * mw * d[k];
      Mb[NS + k] += mw * v[f][k];
    }
  };
  subpairs.clear();
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int itype = type[i];
    const bool fi = fluidself[itype];
    const double xi0 = x[i][0], xi1 = x[i][1], xi2 = (DIM == 3) ? x[i][2] : 0.0;
    const int *jlist = list->firstneigh[i];
    const SaltDEM::ViscousParams *prow = params[itype];
    double Mi[L::NMOM] = {};    // i's sums, stored once
    if (fi) Mi[L::WF] = m[i] * SaltDEM::wendland_c2(DIM, prow[itype].h, 0.0);
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const int jtype = type[j];
      const SaltDEM::ViscousParams &p = prow[jtype];
      const bool fj = fluidself[jtype];
      if (p.mode != SaltDEM::VISCOUS_FLUID || !(fi || fj || sub)) continue;
      const double d[3] = {xi0 - x[j][0], xi1 - x[j][1], (DIM == 3) ? xi2 - x[j][2] : 0.0};
      const double rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (rsq * p.ih2 * p.ih2 >= 1.0 || rsq == 0.0) continue;    // beyond 2h (the list has a skin)
      const double r = sqrt(rsq);
      const double s = 1.0 - r * p.ih2;
      if (sub) subpairs.push_back({i, j, p.kvisc * s * s * s});
      const double w = p.cw * s * s * s;
      const double W = SaltDEM::wendland_c2_s(p.cW, s);
      // i's partner j goes into i's fluid or boundary sums, and i into j's
      if (fi) {
        const double mij = partner_mass<DIM>(radius, i, j);
        SaltDEM::add_moment<DIM>(mij * w, d, fj ? Mi : Mi + NS);
        Mi[fj ? L::WF : L::WB] += mij * W;
      }
      if (fj && (newton_pair || j < nlocal)) {
        const double mji = partner_mass<DIM>(radius, j, i);
        double *Mj = &moment[L::NMOM * j];
        SaltDEM::add_moment<DIM>(mji * w, d, fi ? Mj : Mj + NS);
        Mj[fi ? L::WF : L::WB] += mji * W;
      }
      if (ext && fi != fj) {
        if (fj)
          add_fluid(Mi, j, m[j] * W, d, -1.0);
        else if (newton_pair || j < nlocal)
          add_fluid(&moment[L::NMOM * j], i, m[i] * W, d, 1.0);
      }
    }
    if (fi || ext)
      for (int k = 0; k < L::NMOM; k++) moment[L::NMOM * i + k] += Mi[k];
  }
  if (newton_pair) {
    comm_mode = COMM_PRESSURE;
    comm->reverse_comm(this);
  }
}

/* noslip surface: the offset v_eff - v of each owned boundary particle from its fluid
   partners' sums (kernel_moments; SaltDEM::noslip_offset), 0 for the fluid's own particles
   and for boundary particles without a fluid partner */

template <int DIM> void PairSaltdemViscous::noslip_offsets()
{
  using L = Layout<DIM>;
  const double *const *v = atom->v;
  const double *radius = atom->radius;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    double *o = &slip[3 * i];
    const double *M = &moment[L::NMOM * i];
    if (fluidself[type[i]])
      o[0] = o[1] = o[2] = 0.0;
    else
      SaltDEM::noslip_offset<DIM>(M[L::WF], M, M + L::NS, v[i], radius[i], o);
  }
}

/* the Morris viscosity of the stored pairs as substeps explicit steps of dt/substeps on copies
   of the velocities (positions, volumes and coefficients as in the force pass, the other
   forces of the step held constant), each pair's force -g_ij (u_i - u_j) at every sub-step;
   the mean force over the sub-steps is added to f, so that the integrator's step gives each
   particle the velocity change of the sub-steps.  Atoms that no fix integrates or whose motion
   is prescribed (walls) keep their velocity.  Called by the density fix once all forces of
   the step are in (post_force). */

template <int DIM> void PairSaltdemViscous::viscous_substeps()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double *const *v = atom->v;
  const double *const *x = atom->x;
  double **f = atom->f;
  const int *mask = atom->mask;
  const double *m = atom->rmass;
  const int n = substeps;
  const double hdt = update->dt * force->ftm2v / n;
  const double inv_n = 1.0 / n;

  for (int i = 0; i < nall; i++)
    for (int k = 0; k < 3; k++) usub[3 * i + k] = v[i][k];
  // the other forces of the step, held constant over the sub-steps, and dt/N over the
  // inertial mass of the owned atoms (0 for walls)
  for (int i = 0; i < nlocal; i++) {
    for (int k = 0; k < 3; k++) fother[3 * i + k] = f[i][k];
    const double scale = inertia_scale(mask[i], integrators);
    ksub[i] = (scale > 0.0) ? hdt / (scale * m[i]) : 0.0;
  }

  // the pair weights g_ij = c V_i V_j (the volumes of the force pass, pair_weights), once
  const int *type = atom->type;
  const double *radius = atom->radius;
  for (auto &sp : subpairs) {
    const Weights w = pair_weights<DIM>(radius, sp.i, sp.j, type[sp.i], type[sp.j]);
    sp.c *= w.vi * w.vj;
  }
  // noslip surface: the boundary partners' offsets (of the step's start) add a force that
  // the sub-steps hold constant, as the other forces (its ghosts' parts go home once)
  if (noslip_surface) {
    for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) fsub[i] = 0.0;
    for (const auto &sp : subpairs) {
      // -c (v_i - v_j + o_i - o_j) less the plain -c (v_i - v_j)
      double ov[3] = {0.0, 0.0, 0.0}, fp[3] = {0.0, 0.0, 0.0};
      if (!noslip_pair<DIM>(sp.i, sp.j, type[sp.i], type[sp.j], ov)) continue;
      for (int k = 0; k < DIM; k++) {
        fp[k] = -sp.c * ov[k];
        fsub[3 * sp.i + k] += fp[k];
        if (newton_pair || sp.j < nlocal) fsub[3 * sp.j + k] -= fp[k];
      }
      if (evflag)
        ev_tally_xyz(sp.i, sp.j, nlocal, newton_pair, 0.0, 0.0, fp[0], fp[1], fp[2],
                     x[sp.i][0] - x[sp.j][0], x[sp.i][1] - x[sp.j][1],
                     (DIM == 3) ? x[sp.i][2] - x[sp.j][2] : 0.0);
    }
    comm_mode = COMM_SUBSTEP;
    if (newton_pair) comm->reverse_comm(this);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < DIM; k++) {
        f[i][k] += fsub[3 * i + k];
        fother[3 * i + k] += fsub[3 * i + k];
      }
  }
  const SubPair *begin = subpairs.data(), *end = begin + subpairs.size();
  for (int step = 0; step < n; step++) {
    for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) fsub[i] = 0.0;
    // the pairs come grouped by i (kernel_moments): i's sum is kept in registers
    for (const SubPair *sp = begin; sp < end;) {
      const int i = sp->i;
      const double ui[3] = {usub[3 * i], usub[3 * i + 1], usub[3 * i + 2]};
      double fi[3] = {0.0, 0.0, 0.0};
      for (; sp < end && sp->i == i; ++sp) {
        const int j = sp->j;
        double fp[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < DIM; k++) {
          fp[k] = -sp->c * (ui[k] - usub[3 * j + k]);
          fi[k] += fp[k];
        }
        if (newton_pair || j < nlocal)
          for (int k = 0; k < DIM; k++) fsub[3 * j + k] -= fp[k];
        if (evflag)
          ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fp[0] * inv_n, fp[1] * inv_n,
                       fp[2] * inv_n, x[i][0] - x[j][0], x[i][1] - x[j][1],
                       (DIM == 3) ? x[i][2] - x[j][2] : 0.0);
      }
      for (int k = 0; k < DIM; k++) fsub[3 * i + k] += fi[k];
    }
    comm_mode = COMM_SUBSTEP;
    if (newton_pair) comm->reverse_comm(this);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < DIM; k++) {
        f[i][k] += fsub[3 * i + k] * inv_n;
        usub[3 * i + k] += ksub[i] * (fsub[3 * i + k] + fother[3 * i + k]);
      }
    if (step + 1 < n) comm->forward_comm(this);
  }
  comm_mode = COMM_PRESSURE;
}

void PairSaltdemViscous::grow_arrays()
{
  // (sub-steps may be switched on between runs: saltdem/timestep ... substeps N)
  if (atom->nmax <= nmax && (substeps < 2 || usub) && (!noslip_surface || slip)) return;
  memory->destroy(vol);
  memory->destroy(pmat);
  memory->destroy(moment);
  memory->destroy(fill);
  memory->destroy(mdens);
  memory->destroy(scratch);
  memory->destroy(slip);
  memory->destroy(usub);
  memory->destroy(fsub);
  memory->destroy(ksub);
  memory->destroy(fother);
  nmax = MAX(nmax, atom->nmax);
  memory->create(vol, nmax, "pair:vol");
  if (noslip_surface) {
    memory->create(slip, 3 * nmax, "pair:slip");
    for (int i = 0; i < 3 * nmax; i++) slip[i] = 0.0;
  }
  memory->create(fill, nmax, "pair:fill");
  memory->create(mdens, nmax, "pair:mdens");
  if (substeps > 1) {
    memory->create(usub, 3 * nmax, "pair:usub");
    memory->create(fsub, 3 * nmax, "pair:fsub");
    memory->create(ksub, nmax, "pair:ksub");
    memory->create(fother, 3 * nmax, "pair:fother");
  }
  memory->create(pmat, SaltDEM::NSYM * nmax, "pair:pmat");
  memory->create(moment, NMOM_MAX * nmax, "pair:moment");
  if (!any_fluid) memory->create(scratch, nmax, "pair:scratch");
}

/* the material density m / r^dim of the owned and ghost atoms, which weighs a partner as
   the particle's own material (pair_weights); a disc in a FLUID pair needs a radius */

void PairSaltdemViscous::material_density()
{
  const int nall = atom->nlocal + atom->nghost;
  const double *radius = atom->radius, *m = atom->rmass;
  const int *type = atom->type;
  const int dim = domain->dimension;
  for (int i = 0; i < nall; i++) {
    const double r = radius[i];
    const double a = (dim == 2) ? r * r : r * r * r;
    if (!(a > 0.0) && influid[type[i]])
      error->one(FLERR,
                 "Pair style {}: atom {} of type {} has radius {} in a fluid pair; the fluid law "
                 "weighs its partners by their size: give every disc a positive diameter (set "
                 "... diameter)",
                 name, atom->tag[i], type[i], r);
    mdens[i] = (a > 0.0) ? m[i] / a : 0.0;
  }
}

/* the array the force pass sums d rho / dt into (zeroed here): the density fix's; with no
   FLUID pair (every q is 0) a scratch array.  The OpenMP variant sums per thread and adds
   the threads' sums into the same array. */

double *PairSaltdemViscous::loop_sum()
{
  const int nall = atom->nlocal + atom->nghost;
  if (!any_fluid && !scratch) memory->create(scratch, nmax, "pair:scratch");
  double *sum = any_fluid ? fix_density->drho : scratch;
  for (int i = 0; i < nall; i++) sum[i] = 0.0;
  return sum;
}

int PairSaltdemViscous::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  const int ns = (domain->dimension == 2) ? SaltDEM::nsym<2>() : SaltDEM::nsym<3>();
  int k = 0;
  if (comm_mode == COMM_SUBSTEP) {
    for (int i = 0; i < n; i++)
      for (int c = 0; c < 3; c++) buf[k++] = usub[3 * list[i] + c];
    return k;
  }
  const int nd = noslip_surface ? domain->dimension : 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    buf[k++] = vol[j];
    buf[k++] = fill[j];
    for (int c = 0; c < ns; c++) buf[k++] = pmat[ns * j + c];
    for (int c = 0; c < nd; c++) buf[k++] = slip[3 * j + c];
  }
  return k;
}

void PairSaltdemViscous::unpack_forward_comm(int n, int first, double *buf)
{
  const int ns = (domain->dimension == 2) ? SaltDEM::nsym<2>() : SaltDEM::nsym<3>();
  int k = 0;
  if (comm_mode == COMM_SUBSTEP) {
    for (int i = first; i < first + n; i++)
      for (int c = 0; c < 3; c++) usub[3 * i + c] = buf[k++];
    return;
  }
  const int nd = noslip_surface ? domain->dimension : 0;
  for (int i = first; i < first + n; i++) {
    vol[i] = buf[k++];
    fill[i] = buf[k++];
    for (int c = 0; c < ns; c++) pmat[ns * i + c] = buf[k++];
    for (int c = 0; c < nd; c++) slip[3 * i + c] = buf[k++];
  }
}

int PairSaltdemViscous::nmom() const
{
  // the header cannot include saltdem_contact.h (minimal style headers): Layout's own NS
  static_assert(Layout<2>::NS == SaltDEM::nsym<2>() && Layout<3>::NS == SaltDEM::nsym<3>(),
                "Layout::NS must be SaltDEM::nsym");
  return (domain->dimension == 2) ? Layout<2>::NMOM : Layout<3>::NMOM;
}

int PairSaltdemViscous::pack_reverse_comm(int n, int first, double *buf)
{
  const int nm = nmom();
  int k = 0;
  if (comm_mode == COMM_SUBSTEP) {
    for (int i = first; i < first + n; i++)
      for (int c = 0; c < 3; c++) buf[k++] = fsub[3 * i + c];
    return k;
  }
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < nm; c++) buf[k++] = moment[nm * i + c];
  return k;
}

void PairSaltdemViscous::unpack_reverse_comm(int n, int *list, double *buf)
{
  const int nm = nmom();
  int k = 0;
  if (comm_mode == COMM_SUBSTEP) {
    for (int i = 0; i < n; i++)
      for (int c = 0; c < 3; c++) fsub[3 * list[i] + c] += buf[k++];
    return;
  }
  for (int i = 0; i < n; i++)
    for (int c = 0; c < nm; c++) moment[nm * list[i] + c] += buf[k++];
}

double PairSaltdemViscous::memory_usage()
{
  return PairSaltdem::memory_usage() +
      (2.0 + SaltDEM::NSYM + NMOM_MAX + (scratch ? 1.0 : 0.0) + (usub ? 6.0 : 0.0) +
       (slip ? 3.0 : 0.0)) *
      nmax * sizeof(double) +
      (double) subpairs.capacity() * sizeof(SubPair);
}

/* the dashpots from the viscosity, which may have been changed through extract("eta") since
   the last run (fix adapt, fix saltdem/viscosity) */

void PairSaltdemViscous::derive(int i, int j)
{
  if (setflag[i][j]) {
    // a viscosity set through extract("eta") (fix adapt, fix saltdem/viscosity) passes the
    // bounds of pair_coeff too
    if (!(eta[i][j] > 0.0) || !SaltDEM::in_bounds(eta[i][j]))
      error->all(FLERR,
                 "Pair style {}: eta = {} of types {} {}, set through extract(\"eta\") (fix adapt "
                 "or fix saltdem/viscosity), must be > 0, finite and of a magnitude in [{:g}, "
                 "{:g}]; check the variable or the viscosity that sets it",
                 name, eta[i][j], i, j, SaltDEM::MIN_VALUE, SaltDEM::MAX_VALUE);
  }
  auto &p = params[i][j];
  const double e = eta[i][j];
  p.cw = SaltDEM::wendland_c2_grad_over_r(domain->dimension, p.h > 0.0 ? p.h : 1.0);
  p.ih2 = (p.h > 0.0) ? 0.5 / p.h : 0.0;
  p.cW = SaltDEM::wendland_c2(domain->dimension, p.h > 0.0 ? p.h : 1.0, 0.0);
  p.kvisc = 2.0 * correction * e * p.cw;
  p.kfac = (substeps > 1) ? 0.0 : p.kvisc;    // sub-stepped: not in the force pass
  p.gn = calibration * e;
  p.gt = p.ratio * p.gn;
  if (!std::isfinite(p.cw) || !std::isfinite(p.kvisc) || !std::isfinite(p.gn) ||
      !std::isfinite(p.gt) || !std::isfinite(p.ih2) || !std::isfinite(p.cW))
    error->all(FLERR,
               "Pair style {}: the dashpot coefficients of types {} {} are not finite (2 "
               "correction eta W'(h) = {}, calibration eta = {}, tangential ratio x that = {}) "
               "from eta = {}, h = {}, correction = {}, calibration = {}, tangential ratio = {}; "
               "use values of physical size",
               name, i, j, p.kvisc, p.gn, p.gt, e, p.h, correction, calibration, p.ratio);
  eta[j][i] = e;
}

/* a change of the viscosity or calibration since the last time step check (during a run: fix
   adapt calls reinit(), hence init_one()): the next force computation checks again */

double PairSaltdemViscous::init_one(int i, int j)
{
  const double cut = PairSaltdem::init_one(i, j);
  // a fluid that a boundary holds by its mirrored pressure alone sinks into a line of wall
  // discs and slips on it (docs/validation.md 4.4: 4 m deep, slip length 14 m), and with the
  // fill it still leaks through in time (a disc after 1300 s of a 190 m film): refused
  const auto &p = params[i][j];
  if (p.mode == SaltDEM::VISCOUS_FLUID && p.kn == 0.0 && isfluid[i] != isfluid[j] &&
      !fluid_in_other_substyle(isfluid[i] ? j : i))
    error->all(FLERR,
               "Pair style {}: fluid type {} meets boundary type {} with kn 0: only the "
               "boundary's mirrored pressure would hold the fluid, and a line of wall discs "
               "lets it in (no no-slip base; with 'fill' too, in time); give the pair an "
               "elastic core (kn > 0, e.g. the boundary's kn_wall)",
               name, isfluid[i] ? i : j, isfluid[i] ? j : i);
  const double e = eta[i][j];
  if (setflag[i][j] && i < (int) eta_checked.size() && j < (int) eta_checked[i].size() &&
      (eta_checked[i][j] != e || calibration_checked != calibration)) {
    recheck = true;
    recheck_what = calibration_checked != calibration
        ? fmt::format("the calibration ({:.6g} -> {:.6g})", calibration_checked, calibration)
        : fmt::format("eta of types {} {} ({:.6g} -> {:.6g} Pa s, e.g. by fix adapt)", i, j,
                      eta_checked[i][j], e);
  }
  return cut;
}

/* the saltdem/viscous styles of the run in order: this one alone, or the sub-styles of this
   name under pair hybrid (pair_match ignores the index when the pair is not hybrid) */

std::vector<PairSaltdemViscous *> PairSaltdemViscous::substyles() const
{
  std::vector<PairSaltdemViscous *> out;
  for (auto *s : saltdem_styles(lmp, name))
    if (auto *v = dynamic_cast<PairSaltdemViscous *>(s)) out.push_back(v);
  return out;
}

/* whether type t is a fluid (its own pair FLUID with K > 0) of another saltdem/viscous
   sub-style of pair hybrid: two salts of two sub-styles meet as fluids, not at a wall */

bool PairSaltdemViscous::fluid_in_other_substyle(int t) const
{
  for (auto *s : substyles())
    if (s != this && s->allocated && s->setflag[t][t] &&
        s->params[t][t].mode == SaltDEM::VISCOUS_FLUID && s->params[t][t].K > 0.0)
      return true;
  return false;
}

/* the viscosities and calibration of the last time step check */

void PairSaltdemViscous::limits_checked()
{
  PairSaltdem::limits_checked();
  const int n = allocated ? atom->ntypes : 0;
  eta_checked.assign(n + 1, std::vector<double>(n + 1, 0.0));
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) eta_checked[i][j] = eta[i][j];
  calibration_checked = calibration;
}

/* Limits per type pair.  Elastic: C sqrt(m/kn), C = dtfactor (2 dtfactor against a wall).
   Viscous: an explicit dashpot network is stable while dt < 2 / lambda_max, and Gershgorin
   bounds lambda_max by 2 max sum(gamma) / m.  FLUID: the kernel sums to sum(gamma) =
   7 eta V / h^2 (2D and 3D), which with V = 1/sum W gives dt < S m h^2 / (7 eta V); the
   constant 0.175 S rho h^2 / (correction eta) (viscfactor 1, rho the disc density) is the
   lowest limit measured (bench/stable_limit.py: 0.177 at S 200 near the sound limit,
   0.197-0.211 in channels at S 5-80, 0.22-0.26 in the Expt 1 scene; Gershgorin's bound with
   V = disc/0.7 is 0.1).  CONTACT: a disc's tangential dashpot
   also spins it (SaltDEM::rotation_factor), so dt < m / (g (1 + rot ratio)); measured
   1.26-1.55 times that, so 0.625 of it at viscfactor 1.  The default viscfactor 0.8 leaves a
   margin of 1.25 on both. */

void PairSaltdemViscous::pair_limit(int i, int j, double m, double mv, bool wall, double &best,
                                    std::string &why)
{
  const double rot = SaltDEM::rotation_factor(domain->dimension);
  const double f2v = force->ftm2v;    // (1 in SI) forces and dashpots act on m / ftm2v
  const double e = eta[i][j];
  const auto &p = params[i][j];
  const double c = elastic_factor(wall);
  if (p.kn > 0.0)
    consider_limit(c * sqrt(m / (p.kn * f2v)), best, why, [&] {
      return fmt::format("kn = {:.6g} of types {} {} with the lightest mass {:.6g} "
                         "(dt < {} * sqrt(m/kn){})",
                         p.kn, i, j, m, c, wall ? ", 2 dtfactor against a wall" : "");
    });
  double lim;
  std::string formula;
  if (p.mode == SaltDEM::VISCOUS_FLUID) {
    // V = 1/sum W is not known before the first step: bound it by the
    // disc volume over a packing fraction of 0.7
    // (sub-stepped: the same limit on each of the substeps steps of dt / substeps)
    lim = substeps * viscfactor * 0.175 * mv * p.h * p.h / (correction * e * f2v);
    formula = fmt::format("dt{} < {} * 0.175 S rho h^2 / (correction eta), rho the disc "
                          "density, h = {:.6g}, correction = {:.6g}",
                          substeps > 1 ? fmt::format(" / substeps {}", substeps) : "", viscfactor,
                          p.h, correction);
    // sound: c^2 = K / rho with the inertial density, CFL 0.25 h / c
    if (p.K > 0.0) {
      const double c = sqrt(p.K * f2v / (0.7 * mv));
      consider_limit(0.25 * p.h / c, best, why, [&] {
        return fmt::format("K = {:.6g} of types {} {} (sound speed {:.4g} with the inertial "
                           "density; dt < 0.25 h / c, h = {:.6g}); a larger dt needs a smaller "
                           "K or more inertia",
                           p.K, i, j, c, p.h);
      });
    }
  } else {
    lim = viscfactor * 0.625 * m / (calibration * e * (1.0 + rot * p.ratio) * f2v);
    formula = fmt::format("dt < {} * 0.625 S m / (calibration * eta * (1 + {} * ratio)), "
                          "calibration = {:.6g}, ratio = {:.6g}, lightest mass {:.6g}",
                          viscfactor, rot, calibration, p.ratio, m);
  }
  consider_limit(lim, best, why, [&] {
    // (the factor on S only where the step exceeds the limit: the error, not the log)
    return fmt::format(
        "eta = {:.6g} of types {} {} ({}); a larger dt needs a smaller eta, "
        "more inertia for the viscous discs ('fix saltdem/nve ... inertia "
        "S'{}){}",
        e, i, j, formula,
        update->dt > lim ? fmt::format(" with S >= {:.3g} times the present one", update->dt / lim)
                         : "",
        p.mode == SaltDEM::VISCOUS_FLUID ? " or viscous sub-steps (substeps N)" : "");
  });
}

/* ---------------------------------------------------------------------- */

/* the restart fields: the settings, and per type pair the law, the viscosity and the
   coefficients given (the dashpots cw, ih2, kfac, gn, gt are derived) */

std::vector<std::string> PairSaltdemViscous::setting_names() const
{
  // (the settings of the layout being read: 1 before fill and substeps, 3 before noslip)
  if (layout_read == 1) return {"calibration", "correction", "dtfactor", "viscfactor"};
  if (layout_read == 3)
    return {"calibration", "correction", "dtfactor", "viscfactor", "fill", "substeps"};
  return {"calibration", "correction", "dtfactor", "viscfactor", "fill", "substeps", "noslip"};
}

void PairSaltdemViscous::pack_settings(double *v) const
{
  v[0] = calibration;
  v[1] = correction;
  v[2] = dtfactor;
  v[3] = viscfactor;
  v[4] = fill_max;
  v[5] = substeps;
  v[6] = noslip_surface ? 1.0 : 0.0;
}

void PairSaltdemViscous::unpack_settings(const double *v)
{
  calibration = v[0];
  correction = v[1];
  dtfactor = v[2];
  viscfactor = v[3];
  fill_max = (layout_read == 1) ? DEFAULT_FILL_MAX : v[4];
  substeps = (layout_read == 1) ? 1 : (int) v[5];
  noslip_surface = (layout_read >= 4) && v[6] != 0.0;
}

std::vector<std::string> PairSaltdemViscous::coeff_names() const
{
  return {"law", "eta", "kn", "h", "K", "gap", "tangential"};
}

void PairSaltdemViscous::pack_coeffs(int i, int j, double *v) const
{
  const auto &p = params[i][j];
  const double f[] = {(double) p.mode, eta[i][j], p.kn, p.h, p.K, p.gap, p.ratio};
  for (int k = 0; k < 7; k++) v[k] = f[k];
}

void PairSaltdemViscous::unpack_coeffs(int i, int j, const double *v)
{
  SaltDEM::ViscousParams p{};
  p.mode = (v[0] == SaltDEM::VISCOUS_CONTACT) ? SaltDEM::VISCOUS_CONTACT : SaltDEM::VISCOUS_FLUID;
  eta[i][j] = v[1];
  p.kn = v[2];
  p.h = v[3];
  p.K = v[4];
  p.gap = v[5];
  p.ratio = v[6];
  params[i][j] = p;
}

/* the inertia factor S of the viscous discs: the largest of the integrated atoms of the types
   whose own pair I,I is this style's (the salt), 1 if none is integrated.  Collective. */

double PairSaltdemViscous::find_salt_inertia()
{
  double s = 0.0, all = 0.0;
  const Integrators now = find_integrators();    // (also asked before the run's init)
  if (allocated)
    for (int i = 0; i < atom->nlocal; i++)
      if (setflag[atom->type[i]][atom->type[i]]) s = MAX(s, inertia_scale(atom->mask[i], now));
  MPI_Allreduce(&s, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return (all > 0.0) ? all : 1.0;
}

/* "eta": per type pair viscosity (dim 2), read and changed by fix adapt and
   fix saltdem/viscosity; "calibration": dashpot per unit viscosity; "inertia": the inertia
   factor of the salt's discs as of the last init (find_salt_inertia()) */

void *PairSaltdemViscous::extract(const char *str, int &dim)
{
  if (strcmp(str, "eta") == 0) {
    dim = 2;
    return (void *) eta;
  }
  dim = 0;
  if (strcmp(str, "calibration") == 0) return (void *) &calibration;
  if (strcmp(str, "inertia") == 0) return (void *) &salt_inertia;
  return nullptr;
}
