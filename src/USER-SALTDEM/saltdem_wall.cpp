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

   saltdem/wall: a straight line of touching wall discs, the building block
   of basements, fault faces and end walls for the motion fixes
   (saltdem/blocks and its instances).  The discs are centred on the segment
   from (x0,y0) to (x1,y1), both ends included, at a spacing of at most 2R,
   so no disc of the scene can pass between them.  In 3D the line is
   extruded along z into a strip of touching spheres (the section lies in
   x-y, y up, as in 2D; z runs along strike).
------------------------------------------------------------------------- */

#include "saltdem_wall.h"

#include "saltdem_check.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

static constexpr double MAXWALL = 1e7;               // most discs one command makes
static constexpr double DEFAULT_DENSITY = 2200.0;    // kg/m^3 (units si only)

static const char *usage =
    "saltdem/wall TYPE x0 y0 x1 y1 R [group NAME] [density RHO] [z Z0 Z1 (3D)]";

void SaltdemWall::command(int narg, char **arg)
{
  if (domain->box_exist == 0)
    error->all(FLERR, "saltdem/wall command before simulation box is defined");
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR, "saltdem/wall requires atom style sphere (per-atom radius and mass)");
  if (narg < 6) utils::missing_cmd_args(FLERR, std::string("saltdem/wall; usage: ") + usage, error);

  const int type = utils::inumeric(FLERR, arg[0], false, lmp);
  if (type < 1 || type > atom->ntypes)
    error->all(FLERR, "saltdem/wall: atom type {} is not in 1..{}", type, atom->ntypes);
  const double x0 = utils::numeric(FLERR, arg[1], false, lmp);
  const double y0 = utils::numeric(FLERR, arg[2], false, lmp);
  const double x1 = utils::numeric(FLERR, arg[3], false, lmp);
  const double y1 = utils::numeric(FLERR, arg[4], false, lmp);
  const double r = SaltDEM::numeric(FLERR, arg[5], "saltdem/wall: radius R", lmp);
  if (r <= 0.0) error->all(FLERR, "saltdem/wall: radius R = {} must be > 0", r);

  int igroup = -1;
  double density = 0.0;
  const bool is3d = domain->dimension == 3;
  bool zgiven = false;
  double z0 = 0.0, z1 = 0.0;
  for (int iarg = 6; iarg < narg; iarg += 2) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, std::string("saltdem/wall ") + arg[iarg], error);
    const std::string kw = arg[iarg];
    if (kw == "group") {
      igroup = group->find_or_create(arg[iarg + 1]);
    } else if (kw == "z") {
      if (!is3d)
        error->all(FLERR,
                   "saltdem/wall: 'z Z0 Z1' extrudes a wall along z in a 3D deck; this "
                   "deck is 2D");
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "saltdem/wall z", error);
      z0 = SaltDEM::numeric(FLERR, arg[iarg + 1], "saltdem/wall: z Z0", lmp);
      z1 = SaltDEM::numeric(FLERR, arg[iarg + 2], "saltdem/wall: z Z1", lmp);
      zgiven = true;
      iarg++;
    } else if (kw == "density") {
      density = SaltDEM::numeric(FLERR, arg[iarg + 1], "saltdem/wall: density", lmp);
      if (density <= 0.0) error->all(FLERR, "saltdem/wall: density = {} must be > 0", density);
    } else
      error->all(FLERR, "saltdem/wall: unknown keyword '{}'; usage: {}", kw, usage);
  }
  // the default density is the scenes' rock, in kg/m^3: SI only
  if (density == 0.0) {
    if (strcmp(update->unit_style, "si") != 0)
      error->all(FLERR,
                 "saltdem/wall: the default density {} is in kg/m^3 (units si); under "
                 "units {} give 'density RHO' in the deck's units (mass per area of a disc of "
                 "unit thickness; in 3D per volume)",
                 DEFAULT_DENSITY, update->unit_style);
    density = DEFAULT_DENSITY;
  }

  // both ends must lie in the box, which LAMMPS owns half-open, [lo, hi): a disc on an upper
  // edge of a non-periodic box is lost at the next run
  const double *lo = domain->boxlo, *hi = domain->boxhi;
  auto check = [&](double px, double py) {
    if (px < lo[0] || px >= hi[0] || py < lo[1] || py >= hi[1])
      error->all(FLERR,
                 "saltdem/wall: end point ({}, {}) lies outside the box [{}, {}) x [{}, {}); "
                 "enlarge the box with change_box first",
                 px, py, lo[0], hi[0], lo[1], hi[1]);
  };
  check(x0, y0);
  check(x1, y1);
  if (domain->triclinic) error->all(FLERR, "saltdem/wall does not support triclinic boxes");

  // a wall disc larger than the box is not a wall of this scene (and its ghost cutoff would
  // span the box many times)
  const double extent = MAX(hi[0] - lo[0], hi[1] - lo[1]);
  if (r > extent)
    error->all(FLERR,
               "saltdem/wall: radius R = {} exceeds the box size {}; give the radius in the "
               "units of the box",
               r, extent);

  // 3D: the rows along z.  Periodic in z and no 'z': the period tiled evenly (no sphere on
  // its own image); otherwise Z0 to Z1, both ends included
  double nzd = 1.0, zstart = 0.0, dz = 0.0;
  if (is3d) {
    const bool tile = !zgiven && domain->periodicity[2];
    if (!zgiven && !tile)
      error->all(FLERR, "saltdem/wall: give 'z Z0 Z1' in a box that is not periodic in z");
    if (tile) {
      nzd = ceil((hi[2] - lo[2]) / (2.0 * r) - 1e-9);
      dz = (hi[2] - lo[2]) / nzd;
      zstart = lo[2] + 0.5 * dz;
    } else {
      if (z0 < lo[2] || z0 >= hi[2] || z1 < lo[2] || z1 >= hi[2])
        error->all(FLERR, "saltdem/wall: z {} to {} lies outside the box [{}, {})", z0, z1, lo[2],
                   hi[2]);
      const double nz = fabs(z1 - z0) > 0.0 ? ceil(fabs(z1 - z0) / (2.0 * r) - 1e-9) : 0.0;
      nzd = nz + 1.0;
      dz = nz > 0.0 ? (z1 - z0) / nz : 0.0;
      zstart = z0;
    }
  }

  // the number of discs in 64 bits: a tiny radius on a long line must not wrap around
  const double len = sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0));
  const double nsegd = len > 0.0 ? ceil(len / (2.0 * r) - 1e-9) : 0.0;
  if (!((nsegd + 1.0) * nzd <= MAXWALL))
    error->all(FLERR,
               "saltdem/wall: a line of length {} with discs of radius {} needs {:.4g} wall "
               "discs, more than the {:.0f} one command makes; use a larger radius (the discs "
               "must touch: spacing <= 2R)",
               len, r, (nsegd + 1.0) * nzd, MAXWALL);
  const bigint nseg = (bigint) nsegd, nz = (bigint) nzd, total = (nseg + 1) * nz;
  if ((bigint) atom->nlocal + total > MAXSMALLINT || atom->natoms + total > MAXTAGINT)
    error->all(FLERR,
               "saltdem/wall: {} more wall discs would exceed the number of atoms LAMMPS "
               "can hold; use a larger radius",
               total);
  // new atoms overwrite ghost atoms: clear them and the map first (as create_atoms does)
  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  const int nlocal_previous = atom->nlocal;
  const double *sublo = domain->sublo, *subhi = domain->subhi;
  const int ndim = is3d ? 3 : 2;
  // unit thickness in 2D (set density/disc), a sphere in 3D
  const double mass = is3d ? density * 4.0 * M_PI * r * r * r / 3.0 : density * M_PI * r * r;
  for (bigint kz = 0; kz < nz; kz++)
    for (bigint k = 0; k <= nseg; k++) {
      const double t = nseg ? double(k) / nseg : 0.0;
      double x[3] = {x0 + t * (x1 - x0), y0 + t * (y1 - y0), is3d ? zstart + kz * dz : 0.0};
      bool mine = true;
      for (int d = 0; d < ndim; d++) mine = mine && x[d] >= sublo[d] && x[d] < subhi[d];
      if (!mine) continue;
      atom->avec->create_atom(type, x);
      const int i = atom->nlocal - 1;
      atom->radius[i] = r;
      atom->rmass[i] = mass;
      if (igroup >= 0) atom->mask[i] |= group->bitmask[igroup];
    }

  atom->data_fix_compute_variable(nlocal_previous, atom->nlocal);
  const bigint natoms_previous = atom->natoms;
  bigint nblocal = atom->nlocal;
  MPI_Allreduce(&nblocal, &atom->natoms, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  // every disc of the line lies in the box, so some rank owns it: never fewer, never none
  const bigint made = atom->natoms - natoms_previous;
  if (made != total)
    error->all(FLERR,
               "saltdem/wall: made {} of the {} wall discs from ({}, {}) to ({}, {}) (the "
               "others fell outside every sub-domain); move the end points inside the box",
               made, total, x0, y0, x1, y1);
  if (atom->tag_enable) atom->tag_extend();
  atom->tag_check();
  if (atom->map_style != Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }
  if (comm->me == 0)
    utils::logmesg(lmp, "saltdem/wall: {} wall {} of radius {} from ({}, {}) to ({}, {}){}\n",
                   total, is3d ? "spheres" : "discs", r, x0, y0, x1, y1,
                   is3d ? fmt::format(" in {} rows along z", nz) : "");
}
