"""Open MPI start-up failures, told apart from failures of lmp itself.

On a loaded machine Open MPI sometimes fails to start a process (its singleton or mpirun's
daemons time out): lmp never runs, and the output holds Open MPI's own report ("orte_init
failed ... instead of ORTE_SUCCESS").  That is an infrastructure failure, not a crash of lmp and
not a result: `run` retries it with a back-off, and the callers report one that persists as
such (lmprun.run_cmd fails the test naming it; fuzzlib classifies it `infra`).

Told apart by text: one of Open MPI's start-up messages, and no LAMMPS banner (lmp prints
"LAMMPS (version)" as soon as MPI has started, so a crash of lmp always follows the banner)."""
import subprocess
import time

START_FAILURE_MARKERS = (
    "instead of ORTE_SUCCESS", "orte_init failed", "ompi_rte_init failed", "MPI_INIT failed",
    "An error occurred in MPI_Init", "before MPI_INIT completed",
    "ORTE was unable to reliably start", "ORTE daemon has unexpectedly failed",
    "PMIx_Init failed", "opal_init failed", "mpirun was unable to launch")
BANNER = "LAMMPS ("
TRIES = 3
BACKOFF = (2.0, 6.0)    # seconds before the second and third try


def start_failed(out):
    """True if `out` (stdout + stderr) is Open MPI failing to start, before lmp ran."""
    if isinstance(out, bytes):
        out = out.decode(errors="replace")
    return BANNER not in out and any(m in out for m in START_FAILURE_MARKERS)


def output_of(proc):
    out = (proc.stdout or "") + (proc.stderr or "")
    return out.decode(errors="replace") if isinstance(out, bytes) else out


def run(cmd, tries=TRIES, backoff=BACKOFF, sleep=time.sleep, runner=subprocess.run, **kwargs):
    """subprocess.run(cmd, **kwargs), again after a back-off while it fails because Open MPI
    did not start.  Returns (completed process, number of tries, True if MPI never started)."""
    for k in range(tries):
        proc = runner(cmd, **kwargs)
        if proc.returncode == 0 or not start_failed(output_of(proc)):
            return proc, k + 1, False
        if k + 1 < tries:
            sleep(backoff[min(k, len(backoff) - 1)])
    return proc, tries, True


def describe(proc, tries):
    out = output_of(proc)
    lines = [l.strip() for l in out.splitlines() if any(m in l for m in START_FAILURE_MARKERS)]
    line = " / ".join(dict.fromkeys(lines))    # each once, in order
    return (f"INFRASTRUCTURE FAILURE, not a test result: Open MPI failed to start lmp {tries} "
            f"times (exit {proc.returncode}): {line}")
