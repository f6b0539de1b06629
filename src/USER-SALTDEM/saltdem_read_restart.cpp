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

   saltdem/read_restart FILE [checksum required|optional] [timeout SECONDS]:
   read_restart FILE after two guards.  The file must match its checksum
   file FILE.sha256 (written by fix saltdem/checksum); a mismatch, a missing
   file or (with checksum required) a missing checksum is an error that
   names the other file of an .a/.b pair.  A watchdog ends the process with
   an error if reading takes longer than the timeout: LAMMPS's reader has no
   checks of its own, and a damaged per-atom record can loop forever
   (default: 60 s plus 1 s per 10 MB of file; 0: no watchdog).  A file no
   checksum verified that crashes the reader ends in an error too.
------------------------------------------------------------------------- */

#include "saltdem_read_restart.h"

#include "comm.h"
#include "error.h"
#include "input.h"
#include "platform.h"
#include "saltdem_sha256.h"
#include "utils.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

using namespace LAMMPS_NS;

namespace {

// what the guards on the read print as they end the process (set before the read: a signal
// handler may only write): the watchdog's on SIGALRM, the crash guard's on any other signal
struct Message {
  char text[1024];
  size_t length;
};
Message watchdog_message, crash_message;
int message_fd[2] = {-1, -1};    // screen and log file

extern "C" void read_failed(int sig)
{
  // only async-signal-safe calls here
  const Message &m = (sig == SIGALRM) ? watchdog_message : crash_message;
  for (int fd : message_fd)
    if (fd >= 0 && write(fd, m.text, m.length) < 0) break;
  _exit(1);
}

void set_message(Message &m, const std::string &msg)
{
  m.length = std::min(msg.size(), sizeof(m.text));
  memcpy(m.text, msg.data(), m.length);
}

const int CRASH_SIGNALS[] = {SIGSEGV, SIGBUS, SIGFPE};

// the other file of a restart pair written as NAME.a / NAME.b
std::string other_of_pair(const std::string &file)
{
  const size_t n = file.size();
  if (n < 2 || file[n - 2] != '.') return "";
  if (file[n - 1] == 'a') return file.substr(0, n - 1) + "b";
  if (file[n - 1] == 'b') return file.substr(0, n - 1) + "a";
  return "";
}

// what to do instead, for an error message: the other file of the pair if it checks out
std::string advice(const std::string &file)
{
  const std::string other = other_of_pair(file);
  if (other.empty() || !platform::file_is_readable(other))
    return "start the run again from its beginning (no other restart file of a pair is there)";
  const std::string want = SaltDEM::read_checksum(other);
  if (want.empty())
    return fmt::format("resume from the other file of the pair, {} (it has no checksum file to "
                       "verify it)",
                       other);
  if (want == SaltDEM::sha256_file(other))
    return fmt::format("resume from the other file of the pair, {} (its checksum matches)", other);
  return fmt::format("the other file of the pair, {}, fails its checksum too: start the run "
                     "again from its beginning",
                     other);
}

}    // namespace

void SaltdemReadRestart::command(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR,
               "Illegal saltdem/read_restart command: saltdem/read_restart FILE "
               "[checksum required|optional] [timeout SECONDS]");
  const std::string file = arg[0];
  int required = 0;
  double timeout = -1.0;
  for (int iarg = 1; iarg < narg; iarg += 2) {
    if (iarg + 1 >= narg)
      error->all(FLERR, "saltdem/read_restart: keyword {} needs a value", arg[iarg]);
    if (strcmp(arg[iarg], "checksum") == 0) {
      if (strcmp(arg[iarg + 1], "required") == 0)
        required = 1;
      else if (strcmp(arg[iarg + 1], "optional") == 0)
        required = 0;
      else
        error->all(FLERR, "saltdem/read_restart: checksum {} must be required or optional",
                   arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "timeout") == 0) {
      timeout = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(timeout >= 0.0 && timeout <= 1e6))
        error->all(FLERR, "saltdem/read_restart: timeout {} s must be in [0, 1e6] (0: none)",
                   arg[iarg + 1]);
    } else
      error->all(FLERR, "saltdem/read_restart: unknown keyword {} (checksum or timeout)",
                 arg[iarg]);
  }
  if (strchr(file.c_str(), '%') || strstr(file.c_str(), ".mpiio"))
    error->all(FLERR,
               "saltdem/read_restart: {} is a multi-file or MPI-IO restart; use read_restart",
               file);

  // rank 0 checks the file: 0 ok, 1 missing, 2 mismatch, 3 no checksum, 4 bad checksum file
  int status = 0;
  double bytes = 0.0;
  if (comm->me == 0) {
    if (!platform::file_is_readable(file)) {
      status = 1;
    } else {
      FILE *fp = fopen(file.c_str(), "rb");
      if (fp && fseek(fp, 0, SEEK_END) == 0) bytes = (double) ftell(fp);
      if (fp) fclose(fp);
      const std::string want = SaltDEM::read_checksum(file);
      if (want.empty())
        status = 3;
      else if (want == "?")
        status = 4;
      else if (want != SaltDEM::sha256_file(file))
        status = 2;
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, world);
  MPI_Bcast(&bytes, 1, MPI_DOUBLE, 0, world);
  const std::string sum = SaltDEM::checksum_path(file);
  // what to do instead reads and hashes the other file of the pair: once, on the rank that
  // prints, and only for a message that may be printed (an error, or the watchdog's)
  const std::string hint = (comm->me == 0 && (status != 0 || timeout != 0.0)) ? advice(file)
                                                                              : std::string();
  if (status == 1) error->all(FLERR, "saltdem/read_restart: cannot read {}; {}", file, hint);
  if (status == 2)
    error->all(FLERR,
               "saltdem/read_restart: {} does not match its checksum {} (damaged, or cut short "
               "while written); {}",
               file, sum, hint);
  if (status == 4)
    error->all(FLERR, "saltdem/read_restart: checksum file {} is damaged; {}", sum, hint);
  if (status == 3) {
    if (required)
      error->all(FLERR, "saltdem/read_restart: {} has no checksum file {} (checksum required); {}",
                 file, sum, hint);
    if (comm->me == 0)
      error->warning(FLERR, "saltdem/read_restart: {} has no checksum file {}: not verified", file,
                     sum);
  }

  if (timeout < 0.0) timeout = 60.0 + bytes / 1e7;
  // two guards on the read itself, as LAMMPS's reader checks nothing: a watchdog, and where no
  // checksum verified the file, a crash inside the reader (a damaged per-atom record) reported
  // as an error instead of a bare signal
  const bool watch = timeout > 0.0, guard = status == 3;
  if (watch || guard) {
    // the handlers end the process without flushing: what is buffered goes out now
    message_fd[0] = message_fd[1] = -1;
    if (comm->me == 0) {
      if (screen) {
        fflush(screen);
        message_fd[0] = fileno(screen);
      }
      if (logfile) {
        fflush(logfile);
        message_fd[1] = fileno(logfile);
      }
    }
  }
  struct sigaction act, old_alarm, old_crash[3];
  memset(&act, 0, sizeof(act));
  sigemptyset(&act.sa_mask);
  act.sa_handler = read_failed;
  if (watch) {
    set_message(watchdog_message,
                fmt::format("ERROR: saltdem/read_restart: reading {} did not finish within {:.0f} "
                            "s: the file is damaged; {}\n",
                            file, timeout, hint));
    sigaction(SIGALRM, &act, &old_alarm);
    alarm((unsigned int) (timeout + 0.999));
  }
  if (guard) {
    set_message(crash_message,
                fmt::format("ERROR: saltdem/read_restart: reading {} crashed in LAMMPS's reader: "
                            "the file (not verified, no checksum file) is damaged; {}\n",
                            file, hint));
    for (int k = 0; k < 3; k++) sigaction(CRASH_SIGNALS[k], &act, &old_crash[k]);
  }
  input->one("read_restart " + file);
  if (watch) {
    alarm(0);
    sigaction(SIGALRM, &old_alarm, nullptr);
  }
  if (guard)
    for (int k = 0; k < 3; k++) sigaction(CRASH_SIGNALS[k], &old_crash[k], nullptr);
}
