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

   The deposition of fix saltdem/sediment (SaltdemSedimentDeposit, see the header).
------------------------------------------------------------------------- */

#include "saltdem_sediment_deposit.h"

#include "saltdem_sediment_levels.h"
#include "saltdem_sediment_pockets.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "group.h"
#include "math_const.h"
#include "modify.h"
#include "neighbor.h"

#include <cfloat>

using namespace LAMMPS_NS;
using MathConst::MY_PI;
using SaltDEM::SedimentDisc;
using SaltDEM::SedimentPockets;

SaltdemSedimentDeposit::SaltdemSedimentDeposit(LAMMPS *lmp, Fix *owner) :
    Pointers(lmp), ntype(0), rmin(0.0), rmax(0.0), paper(0), density(0.0), tol(0.01),
    maxper(1000000), epoch_index(-1), epoch_offset(0), area(0.0), roomless(0), maxtag(0), fix(owner)
{
}

/* the pair styles size their cutoffs by the largest disc of each type present at the start of
   a run, and their stable time step by the lightest: the new discs must fit in both */

void SaltdemSedimentDeposit::check_fit()
{
  double loc[2] = {0.0, -DBL_MAX}, all[2];    // largest radius, -(smallest mass) of ntype
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->type[i] == ntype) {
      loc[0] = MAX(loc[0], atom->radius[i]);
      loc[1] = MAX(loc[1], -atom->rmass[i]);
    }
  MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_MAX, world);
  if (all[0] <= 0.0)
    error->all(FLERR,
               "Fix {} {}: no discs of type {} at the start of the run: the pair styles "
               "size their cutoffs and stable time step by the discs present, so the cover "
               "must exist before discs are deposited on it",
               fix->style, fix->id, ntype);
  const double margin = 0.5 * neighbor->skin;
  if (rmax > all[0] + margin)
    error->all(FLERR,
               "Fix {} {}: rmax = {} exceeds the largest disc of type {} ({}) by more "
               "than half the neighbour skin ({}): the pair cutoffs would miss its contacts",
               fix->style, fix->id, rmax, ntype, all[0], margin);
  const double mnew = density * MY_PI * rmin * rmin, mold = -all[1];
  if (mnew < 0.95 * mold)
    error->all(FLERR,
               "Fix {} {}: the lightest new disc (density {} x pi rmin^2 = {} kg/m) is "
               "below 0.95 of the lightest disc of type {} ({}), which sets the stable time "
               "step",
               fix->style, fix->id, density, mnew, ntype, mold);
}

/* ---------------------------------------------------------------------- */

bigint SaltdemSedimentDeposit::deposit(const SaltdemSedimentLevels &lev, double level, bool rate,
                                       double target, int epoch)
{
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  double *radius = atom->radius;
  tagint *tag = atom->tag;
  const double *up = lev.up, *along = lev.along;

  double rloc = 0.0, rall;
  tagint tloc = 0;
  for (int i = 0; i < nlocal; i++) {
    rloc = MAX(rloc, radius[i]);
    tloc = MAX(tloc, tag[i]);
  }
  MPI_Allreduce(&rloc, &rall, 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&tloc, &maxtag, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  // the columns span the window, or with a foreset (deposits outside the window) the box
  double glo = lev.xlo, ghi = lev.xhi;
  if (lev.foreset >= 0.0) lev.box_range(along, glo, ghi);
  const SaltDEM::SedimentFrame frame = {level,
                                        lev.foreset,
                                        lev.xlo,
                                        lev.xhi,
                                        rmin,
                                        rmax,
                                        tol,
                                        {along[0], along[1]},
                                        {up[0], up[1]},
                                        {domain->boxlo[0], domain->boxlo[1]},
                                        {domain->boxhi[0], domain->boxhi[1]}};
  SedimentPockets pk(frame, MAX(rmax, rall), glo, ghi);
  if (pk.span > SedimentPockets::MAX_COLUMNS)
    error->all(FLERR,
               "Fix {} {}: the window ({} to {} m) is more than 1e7 columns of {} m: give "
               "a narrower 'x'",
               fix->style, fix->id, glo, ghi, pk.w);

  // the surface of each column over all ranks
  const int ncol = pk.ncol;
  std::vector<double> sloc(ncol, -DBL_MAX);
  std::vector<double> XX(nlocal), YY(nlocal);
  std::vector<int> cc(nlocal);
  for (int i = 0; i < nlocal; i++) {
    XX[i] = along[0] * x[i][0] + along[1] * x[i][1];
    YY[i] = up[0] * x[i][0] + up[1] * x[i][1];
    cc[i] = pk.column(XX[i]);
    if (cc[i] >= 0) sloc[cc[i]] = MAX(sloc[cc[i]], YY[i] + radius[i]);
  }
  MPI_Allreduce(sloc.data(), pk.surface.data(), ncol, MPI_DOUBLE, MPI_MAX, world);
  pk.survey();

  // gather the discs near the surface from every rank
  std::vector<double> mine;
  for (int i = 0; i < nlocal; i++)
    if (cc[i] >= 0 && pk.near_surface(cc[i], YY[i], radius[i]))
      mine.insert(mine.end(), {(double) tag[i], XX[i], YY[i], radius[i]});
  const int nprocs = comm->nprocs;
  int nmine = (int) mine.size();
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Allgather(&nmine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  bigint total = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = (int) total;
    total += counts[p];
  }
  if (total > MAXSMALLINT)
    error->all(FLERR, "Fix {} {}: too many discs near the surface to gather", fix->style, fix->id);
  std::vector<double> flat(MAX(total, (bigint) 1));
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, flat.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  std::vector<SedimentDisc> discs((size_t) (total / 4));
  for (size_t k = 0; k < discs.size(); k++)
    discs[k] = {flat[4 * k + 1], flat[4 * k + 2], flat[4 * k + 3], flat[4 * k]};
  pk.set_discs(std::move(discs));

  // place the discs, the same on every rank (check their count)
  pk.fill(
      [&] {
        return rng.radius(rmin, rmax, paper);
      },
      rate, target, maxper);
  area = pk.area;
  roomless = pk.roomless ? 1 : 0;
  const bigint nnew = (bigint) (pk.discs.size() - pk.first_new);
  bigint nrange[2] = {nnew, -nnew}, nrange_all[2];
  MPI_Allreduce(nrange, nrange_all, 2, MPI_LMP_BIGINT, MPI_MAX, world);
  if (nrange_all[0] != -nrange_all[1])
    error->all(FLERR, "Fix {} {}: the ranks placed {} to {} discs: their placements differ (a bug)",
               fix->style, fix->id, -nrange_all[1], nrange_all[0]);

  // create those of this rank's sub-domain
  int newmask = 1 | fix->groupbit;
  for (int g : groups) newmask |= group->bitmask[g];
  double *sublo = domain->sublo, *subhi = domain->subhi;
  bigint mycount = 0, allcount;
  for (size_t k = pk.first_new; k < pk.discs.size(); k++) {
    const SedimentDisc &d = pk.discs[k];
    double coord[3] = {along[0] * d.X + up[0] * d.Y, along[1] * d.X + up[1] * d.Y, 0.0};
    if (coord[0] < sublo[0] || coord[0] >= subhi[0] || coord[1] < sublo[1] ||
        coord[1] >= subhi[1] || coord[2] < sublo[2] || coord[2] >= subhi[2])
      continue;
    create(coord, d.r, maxtag + (tagint) (k - pk.first_new) + 1, newmask, epoch);
    mycount++;
  }
  MPI_Allreduce(&mycount, &allcount, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (allcount != nnew)
    error->all(FLERR, "Fix {} {}: {} of {} new discs fell in no sub-domain", fix->style, fix->id,
               nnew - allcount, nnew);
  atom->natoms += nnew;
  if (maxtag + nnew >= MAXTAGINT)
    error->all(FLERR, "Fix {} {}: new atom IDs exceed the largest allowed ID", fix->style, fix->id);
  return nnew;
}

/* a new disc at rest, its per-atom data zero but for the epoch */

void SaltdemSedimentDeposit::create(double *coord, double r, tagint id, int mask, int epoch)
{
  atom->avec->create_atom(ntype, coord);
  const int n = atom->nlocal - 1;
  atom->tag[n] = id;
  atom->mask[n] = mask;
  atom->radius[n] = r;
  atom->rmass[n] = density * MY_PI * r * r;
  for (int k = 0; k < 3; k++) {
    atom->v[n][k] = 0.0;
    atom->omega[n][k] = 0.0;
  }
  for (int q = 0; q < atom->nivector; q++)
    if (atom->ivector[q]) atom->ivector[q][n] = 0;
  for (int q = 0; q < atom->ndvector; q++)
    if (atom->dvector[q]) atom->dvector[q][n] = 0.0;
  for (int q = 0; q < atom->niarray; q++)
    if (atom->iarray[q])
      for (int k = 0; k < atom->icols[q]; k++) atom->iarray[q][n][k] = 0;
  for (int q = 0; q < atom->ndarray; q++)
    if (atom->darray[q])
      for (int k = 0; k < atom->dcols[q]; k++) atom->darray[q][n][k] = 0.0;
  modify->create_attribute(n);
  if (epoch_index >= 0) atom->ivector[epoch_index][n] = epoch_offset + epoch;
}
