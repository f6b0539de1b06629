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

   The damped settling of fix saltdem/sediment (SaltdemSedimentSettle, see the header).
------------------------------------------------------------------------- */

#include "saltdem_sediment_settle.h"

#include "atom.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

SaltdemSedimentSettle::SaltdemSedimentSettle(LAMMPS *lmp) : Pointers(lmp), steps(0), gamma(0.0) {}

void SaltdemSedimentSettle::add(tagint lo, tagint hi)
{
  if (hi >= lo && steps > 0 && gamma > 0.0) spans.push_back({lo, hi, update->ntimestep + steps});
}

void SaltdemSedimentSettle::apply()
{
  if (spans.empty()) return;
  const bigint n = update->ntimestep;
  spans.erase(std::remove_if(spans.begin(), spans.end(),
                             [n](const Span &s) {
                               return s.end < n;
                             }),
              spans.end());
  if (spans.empty()) return;
  double **v = atom->v, **f = atom->f, **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius;
  tagint *tag = atom->tag;
  for (int i = 0; i < atom->nlocal; i++)
    for (const auto &s : spans)
      if (tag[i] >= s.lo && tag[i] <= s.hi) {
        for (int k = 0; k < 2; k++) f[i][k] -= gamma * v[i][k];
        torque[i][2] -= gamma * radius[i] * radius[i] * omega[i][2];
        break;
      }
}

/* the restart layout: the number of spans, then lo, hi, end of each */

void SaltdemSedimentSettle::pack(std::vector<double> &list) const
{
  list.push_back((double) spans.size());
  for (const auto &s : spans)
    list.insert(list.end(), {(double) s.lo, (double) s.hi, (double) s.end});
}

int SaltdemSedimentSettle::unpack(const double *list)
{
  const int ns = (int) list[0];
  spans.clear();
  int k = 1;
  for (int q = 0; q < ns; q++, k += 3)
    spans.push_back({(tagint) list[k], (tagint) list[k + 1], (bigint) list[k + 2]});
  return k;
}
