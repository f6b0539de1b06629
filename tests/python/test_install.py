"""python/ as a Python package: the checkout wrappers run without installing
anything (also through a symlink) and nothing in python/ edits sys.path; the
package installs offline into a venv (python3 -m venv --system-site-packages,
pip install --no-deps --no-build-isolation --no-index) and its console
scripts saltdem-post and saltdem-calibrate run from there."""

import ast
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import saltdem_post

REPO = pathlib.Path(__file__).resolve().parents[2]
PYDIR = REPO / "python"
WRAPPERS = {"saltdem-post": "usage: saltdem-post", "saltdem-calibrate": "usage: saltdem-calibrate",
            "saltdem-section": "usage: saltdem-section"}


def clean_env(**extra):
    """The environment without anything that points Python at the checkout."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "PYTHONSAFEPATH", "SALTDEM_ROOT") and not k.startswith("PIP_")}
    env.update(PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_INPUT="1", **extra)
    return env


def run(cmd, cwd, timeout=300, **env):
    return subprocess.run([str(c) for c in cmd], cwd=cwd, env=clean_env(**env), capture_output=True, text=True,
                          timeout=timeout)


def test_no_sys_path_edits_in_package():
    hits = [f"{p.relative_to(REPO)}:{n}" for p in [*PYDIR.rglob("*.py"), *(PYDIR / w for w in WRAPPERS)]
            for n, line in enumerate(p.read_text().splitlines(), 1) if "sys.path" in line]
    assert not hits, f"sys.path edits in python/: {hits}"


def test_no_private_names_imported_across_modules():
    """A helper that two modules share is public: no module imports another's _name."""
    hits = [f"{p.relative_to(REPO)}:{node.lineno} {alias.name}" for p in PYDIR.rglob("*.py")
            for node in ast.walk(ast.parse(p.read_text())) if isinstance(node, ast.ImportFrom)
            for alias in node.names if alias.name.startswith("_") and not alias.name.startswith("__")]
    assert not hits, f"private names imported across modules: {hits}"


def test_calibration_looks_for_the_checkout_only_when_a_command_needs_it(tmp_path):
    """Importing the calibration, its parser and 'report' never look for the checkout (an
    installed package outside one works); a command that runs LAMMPS does."""
    probe = ("import sys\nimport saltdem_post.checkout as c\n"
             "def looked():\n    sys.exit('looked for the checkout')\n"
             "c.find_repo = looked\n"
             "from saltdem_post.calibration import cli\n"
             "print(cli.main(['-q', '-o', sys.argv[1], 'report']))\n"
             "cli.main(['-q', '-o', sys.argv[1], 'biaxial'])\n")
    res = run([sys.executable, "-c", probe, tmp_path / "cal"], cwd=tmp_path, PYTHONPATH=str(PYDIR))
    assert res.stdout.split() == ["2"], res.stdout + res.stderr
    assert "no results.json" in res.stderr and "looked for the checkout" in res.stderr, res.stderr


def test_version_is_the_packages():
    assert saltdem_post.__version__ and "dynamic" in (PYDIR / "pyproject.toml").read_text()


@pytest.mark.parametrize("name", sorted(WRAPPERS))
@pytest.mark.parametrize("how", ["checkout", "symlink"])
def test_checkout_wrappers(tmp_path, name, how):
    """The wrappers import the package next to them (Python puts the script's
    directory, symlinks resolved, on the module path): from the checkout and
    through a symlink elsewhere, with no PYTHONPATH and another cwd."""
    script = PYDIR / name
    if how == "symlink":
        (tmp_path / "bin").mkdir()
        link = tmp_path / "bin" / name
        link.symlink_to(script)
        script = link
    res = run([sys.executable, script, "-h"], cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert WRAPPERS[name] in res.stdout


def _copy_python(dest: pathlib.Path) -> pathlib.Path:
    return pathlib.Path(shutil.copytree(PYDIR, dest, ignore=shutil.ignore_patterns(
        "__pycache__", "*.pyc", "build", "dist", "*.egg-info")))


def _make_venv(path: pathlib.Path) -> pathlib.Path:
    """A venv with its own pip that sees Debian's numpy/scipy/matplotlib; skips
    only when venv or ensurepip (Debian: python3-venv) is not there."""
    try:
        import ensurepip  # noqa: F401
        import venv  # noqa: F401
    except ImportError as exc:
        pytest.skip(f"no venv/ensurepip module ({exc}): install python3-venv (scripts/setup.sh)")
    res = run([sys.executable, "-m", "venv", "--system-site-packages", path], cwd=path.parent)
    if res.returncode != 0 and "ensurepip" in (res.stdout + res.stderr):
        pytest.skip("python3 -m venv cannot install pip (ensurepip not available): install python3-venv "
                    "(scripts/setup.sh)")
    assert res.returncode == 0, res.stdout + res.stderr
    py = path / "bin" / "python"
    if run([py, "-m", "pip", "--version"], cwd=path.parent).returncode != 0:
        pytest.skip("no pip in the venv: install python3-pip and python3-venv (scripts/setup.sh)")
    # --no-build-isolation builds with what the venv sees: setuptools, and for setuptools < 70.1
    # the wheel package (Debian's python3-wheel, which python3-pip pulls in)
    probe = "import setuptools\ntry:\n import setuptools.command.bdist_wheel\nexcept ImportError:\n import wheel.bdist_wheel"
    res = run([py, "-c", probe], cwd=path.parent)
    if res.returncode != 0:
        pytest.skip(f"{sys.executable}'s venv cannot build a wheel offline (setuptools, or wheel for "
                    f"setuptools < 70.1, missing: {res.stderr.strip().splitlines()[-1]}): install "
                    "python3-setuptools and python3-wheel (scripts/setup.sh)")
    return py


def test_pip_install_console_scripts(tmp_path, fixture_path):
    src = _copy_python(tmp_path / "src")
    py = _make_venv(tmp_path / "venv")
    bindir = py.parent
    work = tmp_path / "work"
    work.mkdir()

    res = run([py, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "--no-index", src], cwd=work)
    assert res.returncode == 0, res.stdout + res.stderr

    # the installed package, not the checkout's, and with its calibration subpackage
    res = run([py, "-c", "import saltdem_post, saltdem_post.calibration.report as r, saltdem_post.dump as d; "
                         "print(saltdem_post.__file__); print(r.__file__); print(d.read_ave_chunk.__module__); "
                         "print(saltdem_post.__version__)"], cwd=work)
    assert res.returncode == 0, res.stderr
    lines = res.stdout.split()
    venv = str((tmp_path / "venv").resolve())
    assert lines[0].startswith(venv) and lines[1].startswith(venv), res.stdout
    assert lines[2] == "saltdem_post.dump" and lines[3] == saltdem_post.__version__

    for name, usage in WRAPPERS.items():
        res = run([bindir / name, "-h"], cwd=work)
        assert res.returncode == 0, res.stderr
        assert usage in res.stdout
    res = run([bindir / "saltdem-post", "--version"], cwd=work)
    assert res.returncode == 0 and saltdem_post.__version__ in res.stdout

    res = run([bindir / "saltdem-post", "info", fixture_path, "-o", work / "info"], cwd=work)
    assert res.returncode == 0, res.stderr
    assert "553 atoms" in res.stdout and (work / "info" / "info.json").exists()

    # installed, saltdem-calibrate finds the checkout from the current directory (or SALTDEM_ROOT),
    # and says so clearly outside one
    res = run([bindir / "saltdem-calibrate", "-q", "-o", work / "cal", "--lmp", sys.executable, "biaxial"],
              cwd=work)
    assert res.returncode == 2 and "no SaltDEM checkout" in res.stderr, res.stdout + res.stderr
    probe = ("from saltdem_post.checkout import find_repo; p = find_repo(); "
             "print(p, (p / 'examples' / 'calibration').is_dir())")
    for cwd, env in ((REPO / "docs", {}), (work, {"SALTDEM_ROOT": str(REPO)})):
        res = run([py, "-c", probe], cwd=cwd, **env)
        assert res.returncode == 0, res.stderr
        assert res.stdout.split() == [str(REPO), "True"], res.stdout
