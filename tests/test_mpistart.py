"""Open MPI start-up failures are retried and reported as infrastructure failures, told apart
from crashes of lmp by their text (tests/mpistart.py)."""
import subprocess
from types import SimpleNamespace

import mpistart
from fuzzlib import classify
from lmprun import lmp_path

# Open MPI 4.1's report when a process fails to start (as seen on a loaded machine)
ORTE_FAILURE = """--------------------------------------------------------------------------
It looks like orte_init failed for some reason; your parallel process is
likely to abort.  There are many reasons that a parallel process can
fail during orte_init; some of which are due to configuration or
environment problems.  This failure appears to be an internal failure;
here's some additional information (which may only be relevant to an
Open MPI developer):

  orte_ess_init failed
  --> Returned value Error (-1) instead of ORTE_SUCCESS
--------------------------------------------------------------------------
*** An error occurred in MPI_Init
*** on a NULL communicator
*** MPI_ERRORS_ARE_FATAL (processes in this communicator will now abort,
***    and potentially your MPI job)
"""
BANNER = "LAMMPS (4 Feb 2025 - Update 2)\n  using 1 OpenMP thread(s) per MPI task\n"


def test_start_failure_is_infra_not_crash():
    assert mpistart.start_failed(ORTE_FAILURE)
    assert classify(1, ORTE_FAILURE).kind == "infra"
    # the same text after lmp started is lmp's failure: a crash, whatever the words
    assert not mpistart.start_failed(BANNER + ORTE_FAILURE)
    assert classify(1, BANNER + ORTE_FAILURE).kind == "crash"
    # a crash of lmp and an exit without an ERROR line stay crashes
    assert classify(-11, BANNER + "Segmentation fault\n").kind == "crash"
    assert classify(1, BANNER + "no error line\n").kind == "crash"
    assert classify(1, BANNER + "ERROR: Illegal pair_coeff command (src/pair.cpp:1)\n").kind == "error"


def fake_runner(outputs):
    """A subprocess.run stand-in returning (rc, stderr) pairs in turn; records the calls."""
    calls = []

    def run(cmd, **kwargs):
        rc, err = outputs[min(len(calls), len(outputs) - 1)]
        calls.append(cmd)
        return SimpleNamespace(returncode=rc, stdout="", stderr=err)
    return run, calls


def test_retried_then_passes():
    run, calls = fake_runner([(1, ORTE_FAILURE), (0, BANNER)])
    slept = []
    proc, tries, failed = mpistart.run(["lmp"], runner=run, sleep=slept.append)
    assert (proc.returncode, tries, failed) == (0, 2, False) and len(calls) == 2
    assert slept == [mpistart.BACKOFF[0]]


def test_persistent_failure_is_reported_as_infrastructure():
    run, calls = fake_runner([(1, ORTE_FAILURE)])
    proc, tries, failed = mpistart.run(["lmp"], runner=run, sleep=lambda s: None)
    assert failed and tries == mpistart.TRIES == len(calls)
    msg = mpistart.describe(proc, tries)
    assert msg.startswith("INFRASTRUCTURE FAILURE") and "ORTE_SUCCESS" in msg


def test_failure_of_lmp_is_not_retried():
    run, calls = fake_runner([(1, BANNER + "ERROR: something (src/x.cpp:1)\n")])
    proc, tries, failed = mpistart.run(["lmp"], runner=run, sleep=lambda s: None)
    assert (tries, failed, len(calls)) == (1, False, 1)


def test_real_start_failure_is_recognised(tmp_path):
    """Open MPI made to fail in MPI_Init for real (an unknown point-to-point component) gives a
    text the classifier calls infra; lmp itself never ran (a deck on standard input would
    print the banner first thing)."""
    env = {"PATH": "/usr/bin:/bin", "OMPI_MCA_pml": "nosuchcomponent"}
    p = subprocess.run([lmp_path(), "-log", "none"], input="print 'ran'\n", cwd=tmp_path,
                       capture_output=True, text=True, env=env, timeout=60)
    out = p.stdout + p.stderr
    assert p.returncode != 0 and mpistart.BANNER not in out, out[-2000:]
    assert mpistart.start_failed(out), out[-2000:]
    assert classify(p.returncode, out).kind == "infra"
