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

   fix ID group saltdem/checksum: a SHA-256 checksum file (FILE.sha256, the
   format of sha256sum) beside every restart file that the restart command
   writes, so that saltdem/read_restart can refuse a damaged or cut-short
   file before LAMMPS reads it.  LAMMPS writes the file at the end of a step,
   after every fix has run; the checksum follows at the next step's
   end_of_step() (or at the end of the run), so for one step the old checksum
   stands beside the new file, which a resume then refuses like any other
   mismatch.
------------------------------------------------------------------------- */

#include "fix_saltdem_checksum.h"

#include "comm.h"
#include "error.h"
#include "output.h"
#include "saltdem_sha256.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemChecksum::FixSaltdemChecksum(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), seen(-1), nwritten(0)
{
  if (narg != 3)
    error->all(FLERR,
               "Illegal fix saltdem/checksum command: it takes no arguments (fix ID group "
               "saltdem/checksum)");
  nevery = 1;
  scalar_flag = 1;
  extscalar = 0;
  global_freq = 1;
}

int FixSaltdemChecksum::setmask()
{
  return END_OF_STEP | POST_RUN;
}

void FixSaltdemChecksum::init()
{
  if (!output->restart_flag) {
    if (comm->me == 0)
      error->warning(FLERR, "Fix saltdem/checksum: no restart command, no file to checksum");
    return;
  }
  for (const char *f : {output->restart1, output->restart2a, output->restart2b})
    if (f && (strchr(f, '%') || strstr(f, ".mpiio")))
      error->all(FLERR,
                 "Fix saltdem/checksum: restart file {} is written by several processors or "
                 "MPI-IO; checksums need a single file per restart (no '%' or .mpiio)",
                 f);
  // a file written before this fix existed keeps whatever checksum it has
  if (seen < 0) seen = output->last_restart;
}

void FixSaltdemChecksum::setup(int)
{
  check();
}

void FixSaltdemChecksum::end_of_step()
{
  check();
}

void FixSaltdemChecksum::post_run()
{
  check();
}

/* the files of the last restart output, if it is newer than the last checksum */

void FixSaltdemChecksum::check()
{
  if (!output->restart_flag || output->last_restart <= seen) return;
  const bigint step = output->last_restart;
  seen = step;
  if (output->restart_flag_single) {
    std::string file = output->restart1;
    const size_t star = file.find('*');
    if (star != std::string::npos) file.replace(star, 1, std::to_string(step));
    sum(file);
  }
  // Output toggles after each write: toggle 1 means restart2a was the last written
  if (output->restart_flag_double)
    sum(output->restart_toggle ? output->restart2a : output->restart2b);
}

void FixSaltdemChecksum::sum(const std::string &file)
{
  int ok = 1;
  if (comm->me == 0) {
    const std::string digest = SaltDEM::sha256_file(file);
    ok = !digest.empty() && SaltDEM::write_checksum(file, digest);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, world);
  if (!ok)
    error->all(FLERR,
               "Fix saltdem/checksum: cannot read restart file {} or write {}: is the directory "
               "writable and the disk not full?",
               file, SaltDEM::checksum_path(file));
  nwritten++;
}

/* the number of checksum files written */

double FixSaltdemChecksum::compute_scalar()
{
  return nwritten;
}
