/* -*- c++ -*- ----------------------------------------------------------
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

   SHA-256 (FIPS 180-4) of a file, and the checksum file beside a restart
   file: one line "<64 hex digits>  <file name>", the format of coreutils'
   sha256sum, so that `sha256sum -c FILE.sha256` checks it too.  LAMMPS
   restart files carry no checksum of their own.  Not a style; no LAMMPS
   classes.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SHA256_H
#define LMP_SALTDEM_SHA256_H

#include <string>

namespace SaltDEM {

// hex digest of the file's bytes; empty if it cannot be read
std::string sha256_file(const std::string &path);

// hex digest of a byte string (for tests of the implementation)
std::string sha256_bytes(const std::string &bytes);

// name of the checksum file of a restart file
inline std::string checksum_path(const std::string &file)
{
  return file + ".sha256";
}

// writes the checksum file of `file` (through a temporary file and a rename,
// so that it is either the old one or the new one); false if it cannot
bool write_checksum(const std::string &file, const std::string &digest);

// the digest recorded in the checksum file of `file`: empty if there is no
// such file, "?" if it is not in the expected format
std::string read_checksum(const std::string &file);

}    // namespace SaltDEM

#endif
