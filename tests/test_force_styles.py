"""Force-style regression tests of the package's pair styles, in the YAML form of LAMMPS's
unittest/force-styles (its test_pair_style.cpp reads the same keys).

Each tests/force-styles/*.yaml holds a deck - pre_commands, the input file, pair_style,
pair_coeff, post_commands - and what it gave: the pair energy (init_vdwl, init_coul), the pair's
virial (init_stress: xx yy zz xy xz yz) and the force on every atom (init_forces) at `run 0`,
and the same after 4 steps (run_*).  The 4 steps integrate with `fix 1 all ${integrator}`
where LAMMPS's harness has `fix 1 all nve` (which does not turn discs): the input file's default
is fix saltdem/nve, a YAML may set another in its pre_commands.  Every YAML is run as LAMMPS's
harness runs it, each variant against the same reference:

  plain        newton on; also the sum of compute pe/atom against the pair energy
  newton_off   newton off
  omp          the /omp styles (-sf omp -pk omp 2, 2 threads), newton on and off
  mpi          2 MPI ranks
  restart      read_restart of the plain run's file written after `run 0` (pair_coeff again
               only where the style keeps none), `run 0`; then `pair_modify nofdotr`; then fix
               adapt scaling every `extract` parameter by 1 (the style must hand it out)

A variant whose styles (`prerequisites`, with /omp for the omp variants) this lmp lacks, or
that the YAML names in skip_tests, is skipped.  Errors are relative, |a - b| / min(|a|, |b|)
(absolute where either is 0), against `epsilon` times LAMMPS's factor for the quantity and
variant (FACTORS); each YAML's epsilon is about 5 times the largest error its variants showed
when it was written (the newton off runs: sums in another order).  The 2d virial is read
through compute pressure NULL pair, which reports no zz, xz, yz: they are 0 in 2d, and
compared so.  LAMMPS's write_data variant is left out: a data file holds no contact history.

The comparison must be able to fail: a copy of a YAML with one reference value altered, or run
with one coefficient altered, fails it; and every coefficient of every YAML moves its forces
(so the deck puts every term of the laws to work and the reference checks them all).

SALTDEM_FORCE_YAML_GENERATE=1 rewrites the results of every YAML from the current build before
the comparisons (stamping lammps_version and date_generated), as LAMMPS's `-u` does; so does
`python3 tests/test_force_styles.py [YAML ...]`, also for a new YAML that has only its deck.
The runs go SALTDEM_FORCE_JOBS (default 3) at a time.
"""
import os
import pathlib
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import pytest
import yaml

if __name__ == "__main__":    # as a script: what pytest.ini's pythonpath gives pytest
    sys.path[:0] = [str(pathlib.Path(__file__).resolve().parents[1] / d)
                    for d in ("tests", "python")]
from lmprun import ROOT, lmp_path, run_lmp  # noqa: E402

HERE = ROOT / "tests" / "force-styles"
CASES = sorted(HERE.glob("*.yaml"))
GENERATE = os.environ.get("SALTDEM_FORCE_YAML_GENERATE", "") not in ("", "0")
JOBS = int(os.environ.get("SALTDEM_FORCE_JOBS", "3"))    # lmp runs at a time

# LAMMPS's factors of epsilon (test_pair_style.cpp): stage -> (forces, stress, energy); the
# /omp variant also multiplies epsilon by 5
FACTORS = {
    "plain": {"init": (1, 1, 1), "run": (5, 1, 1)},
    "newton_off": {"init": (1, 3, 1), "run": (5, 1, 1)},
    "omp": {"init": (5, 50, 5), "run": (25, 50, 5)},    # 5 x (1, 10, 1), 5 x (5, 10, 1)
    "omp_newton_off": {"init": (5, 50, 5), "run": (25, 50, 5)},
    "mpi": {"init": (1, 3, 1), "run": (5, 3, 1)},
    "restart": {"restart": (1, 1, 1), "nofdotr": (1, 1, 1), "extract": (1, 1, 1)},
}
# the reference stage each stage is compared with
REFERENCE = {"init": "init", "run": "run", "restart": "init", "nofdotr": "init",
             "extract": "init"}

MEASURE = """compute fs_pe all pe/atom pair
compute fs_sum all reduce sum c_fs_pe
compute fs_p all pressure NULL pair
variable fs_xx equal c_fs_p[1]*vol
variable fs_yy equal c_fs_p[2]*vol
variable fs_zz equal c_fs_p[3]*vol
variable fs_xy equal c_fs_p[4]*vol
variable fs_xz equal c_fs_p[5]*vol
variable fs_yz equal c_fs_p[6]*vol
thermo_style custom step evdwl ecoul c_fs_sum v_fs_xx v_fs_yy v_fs_zz v_fs_xy v_fs_xz v_fs_yz
thermo_modify format float %.17g norm no
"""
STRESS_COLUMNS = ["v_fs_xx", "v_fs_yy", "v_fs_zz", "v_fs_xy", "v_fs_xz", "v_fs_yz"]
RUN_STEPS = """fix 1 all ${integrator}
thermo 2
run 4 post no
"""
RESULT_KEYS = ["natoms", "init_vdwl", "init_coul", "init_stress", "init_forces", "run_vdwl",
               "run_coul", "run_stress", "run_forces"]


def dump(stage):
    return (f"write_dump all custom {stage}.dump id fx fy fz modify sort id "
            "format float %.17g\n")


# ---------------------------------------------------------------------------------------------
# the YAML
# ---------------------------------------------------------------------------------------------

def lines(value):
    """The commands of a block (None or text) as a list of non-empty lines."""
    return [s.strip() for s in (value or "").splitlines() if s.strip()]


def parse_forces(text):
    """{id: (fx, fy, fz)} of a forces block."""
    return {int(w[0]): tuple(float(v) for v in w[1:4]) for w in map(str.split, lines(text))}


class Config:
    """One YAML file: its deck and, once generated, its reference results."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        self.raw = yaml.safe_load(self.path.read_text())
        r = self.raw
        self.epsilon = float(r["epsilon"])
        self.skip = set((r.get("skip_tests") or "").split())
        self.prerequisites = [tuple(s.split()[:2]) for s in lines(r.get("prerequisites"))]
        self.pre = lines(r.get("pre_commands"))
        self.post = lines(r.get("post_commands"))
        self.input_file = r["input_file"]
        self.pair_style = str(r["pair_style"]).strip()
        self.pair_coeff = lines(r.get("pair_coeff"))
        self.extract = [tuple(s.split()) for s in lines(r.get("extract"))]
        self.has_results = all(k in r for k in RESULT_KEYS)

    def reference(self, stage):
        """Result of a stage ('init' or 'run') as the YAML holds it."""
        r = self.raw
        if not self.has_results:
            pytest.fail(f"{self.path.name} holds no results: generate them "
                        "(SALTDEM_FORCE_YAML_GENERATE=1 or python3 tests/test_force_styles.py)")
        stress = [float(v) for v in str(r[f"{stage}_stress"]).split()]
        return Result(float(r[f"{stage}_vdwl"]), float(r[f"{stage}_coul"]), None, stress,
                      parse_forces(r[f"{stage}_forces"]))


class Result:
    """What a stage gave: pair energies, the sum of pe/atom, the pair virial, forces by id."""

    def __init__(self, vdwl, coul, pe_sum, stress, forces):
        self.vdwl, self.coul, self.pe_sum = vdwl, coul, pe_sum
        self.stress, self.forces = list(stress), dict(forces)


def emit_block(key, text):
    """A block as libyaml writes it for LAMMPS: a literal scalar with the non-specific tag."""
    if not text:
        return f'{key}: ! ""\n'
    head = "|" + ("2" if text[0] == " " else "") + ("" if text.endswith("\n") else "-")
    body = "".join("  " + s + "\n" for s in text.rstrip("\n").split("\n"))
    return f"{key}: ! {head}\n{body}"


def number(v):
    """A float as fmt's "{}" writes it (the shortest exact form, no trailing .0)."""
    s = repr(float(v))
    return s[:-2] if s.endswith(".0") else s


def stress_text(stress):
    return " ".join(f"{0.0 if abs(s) < 1e-13 else s:23.16e}" for s in stress)


def forces_text(forces):
    return "".join(f"{i:3d} {f[0]:23.16e} {f[1]:23.16e} {f[2]:23.16e}\n"
                   for i, f in sorted(forces.items()))


def write_yaml(cfg, version, init, run):
    """The YAML of cfg with the results init and run, in LAMMPS's key order and layout."""
    r = cfg.raw
    out = ["---\n", f"lammps_version: {version}\n"]
    if r.get("tags"):
        out.append(f"tags: {r['tags']}\n")
    out += [f"date_generated: {time.ctime()}\n", f"epsilon: {number(cfg.epsilon)}\n",
            f"skip_tests: {' '.join(sorted(cfg.skip))}".rstrip() + "\n"]
    for key in ("prerequisites", "pre_commands", "post_commands"):
        out.append(emit_block(key, r.get(key) or ""))
    out += [f"input_file: {cfg.input_file}\n", f"pair_style: {cfg.pair_style}\n",
            emit_block("pair_coeff", r.get("pair_coeff") or ""),
            emit_block("extract", r.get("extract") or ""), f"natoms: {len(init.forces)}\n"]
    for stage, res in (("init", init), ("run", run)):
        out += [f"{stage}_vdwl: {number(res.vdwl)}\n", f"{stage}_coul: {number(res.coul)}\n",
                emit_block(f"{stage}_stress", stress_text(res.stress)),
                emit_block(f"{stage}_forces", forces_text(res.forces))]
    out.append("...\n")
    cfg.path.write_text("".join(out))


# ---------------------------------------------------------------------------------------------
# running the decks
# ---------------------------------------------------------------------------------------------

def run(deck, workdir, **kwargs):
    """run_lmp, again after a minute while the executable is being rebuilt (missing or busy)."""
    pathlib.Path(workdir).mkdir(parents=True, exist_ok=True)
    for _ in range(3):
        if os.path.isfile(lmp_path()):
            try:
                r = run_lmp(deck, workdir, timeout=300, **kwargs)
            except OSError as e:    # ETXTBSY: the linker is writing it
                if "Text file busy" not in str(e):
                    raise
            else:
                if "Text file busy" not in r.out:
                    return r
        time.sleep(60)
    pytest.fail(f"{lmp_path()} stayed missing or busy (a rebuild?)")


def fresh_deck(cfg, style=None, coeffs=None, tag="", restart=True):
    """The deck of the plain, newton off, /omp and MPI variants: run 0 (dump {tag}init.dump),
    a restart file, 4 steps (dump {tag}run.dump); style and coeffs replace the YAML's."""
    return "\n".join([f"variable input_dir index {HERE}", *cfg.pre,
                      f"include {HERE / cfg.input_file}", f"pair_style {style or cfg.pair_style}",
                      *(f"pair_coeff {c}" for c in (coeffs or cfg.pair_coeff)), *cfg.post,
                      MEASURE, "run 0 post no", dump(f"{tag}init"),
                      "write_restart init.restart" if restart else "", RUN_STEPS,
                      dump(f"{tag}run")])


def restart_deck(cfg, restart, with_coeffs):
    extract = []
    for k, (name, _dim) in enumerate(cfg.extract):
        style = cfg.pair_style.split()[0]
        extract.append(f"fix fs_adapt{k} all adapt 0 pair {style} {name} * * v_fs_one "
                       "scale yes reset yes")
    return "\n".join(["newton on", f"read_restart {restart}",
                      *(f"pair_coeff {c}" for c in (cfg.pair_coeff if with_coeffs else [])),
                      *cfg.post, MEASURE, "run 0 post no", dump("restart"),
                      "pair_modify nofdotr", "run 0 post no", dump("nofdotr"),
                      "variable fs_one equal 1.0", *extract, "run 0 post no", dump("extract")])


def read_dump(path):
    text = path.read_text().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(w[0]): tuple(float(v) for v in w[1:4]) for w in (s.split() for s in text) if w}


def results(r, stages):
    """{stage: Result} of a run whose thermo tables and dumps come in the order of stages."""
    assert r.rc == 0, f"lmp failed (rc={r.rc}): {r.error()}\n{r.out[-3000:]}"
    out = {}
    for k, stage in enumerate(stages):
        t = r.thermo(k)
        last = {c: v[-1] for c, v in t.items()}
        out[stage] = Result(last["E_vdwl"], last["E_coul"], last["c_fs_sum"],
                            [last[c] for c in STRESS_COLUMNS],
                            read_dump(r.workdir / f"{stage}.dump"))
    return out


def run_variant(cfg, variant, workdir, restart=None):
    """{stage: Result} of one variant of cfg, run in workdir."""
    if variant == "restart":
        r = run(restart_deck(cfg, restart, False), workdir)
        # LAMMPS's harness gives pair_coeff again where the style keeps no coefficients in
        # the restart file (pair hybrid): the same, told by the error
        if r.rc != 0 and "All pair coeffs are not set" in (r.error() or ""):
            r = run(restart_deck(cfg, restart, True), workdir)
        return results(r, ["restart", "nofdotr", "extract"])
    newton = "off" if variant.endswith("newton_off") else "on"
    r = run(fresh_deck(cfg), workdir, np=2 if variant == "mpi" else 1,
            omp=2 if variant.startswith("omp") else 0, newton_pair=newton)
    return results(r, ["init", "run"])


def lammps_version(out):
    line = next(s for s in out.splitlines() if s.startswith("LAMMPS ("))
    return line[len("LAMMPS ("):].rstrip(")").split(" - ")[0]


def generate(path, workdir):
    """Rewrite the results of the YAML at path from the current build."""
    cfg = Config(path)
    r = run(fresh_deck(cfg), pathlib.Path(workdir))
    res = results(r, ["init", "run"])
    write_yaml(cfg, lammps_version(r.out), res["init"], res["run"])


# ---------------------------------------------------------------------------------------------
# the comparison (LAMMPS's EXPECT_FP_LE_WITH_EPS, EXPECT_FORCES, EXPECT_STRESS)
# ---------------------------------------------------------------------------------------------

def rel_error(a, b):
    div = min(abs(a), abs(b))
    return abs(a - b) if div == 0.0 else abs(a - b) / div


def compare(got, ref, eps, factors, label):
    """The failures (text) of Result got against Result ref: forces, stress and energy with
    the tolerances eps * factors (forces, stress, energy)."""
    ff, fs, fe = (eps * f for f in factors)
    bad = []
    if got.forces.keys() != ref.forces.keys():
        return [f"{label}: atom ids {sorted(got.forces)} != reference {sorted(ref.forces)}"]
    for i in sorted(ref.forces):
        for c, (a, b) in zip("xyz", zip(got.forces[i], ref.forces[i])):
            if rel_error(a, b) > ff:
                bad.append(f"{label}: f{c} of atom {i} = {a!r}, reference {b!r} "
                           f"(error {rel_error(a, b):.3g} > {ff:.3g})")
    for c, a, b in zip(["xx", "yy", "zz", "xy", "xz", "yz"], got.stress, ref.stress):
        if rel_error(a, b) > fs:
            bad.append(f"{label}: stress {c} = {a!r}, reference {b!r} "
                       f"(error {rel_error(a, b):.3g} > {fs:.3g})")
    for name, a, b in (("vdwl", got.vdwl, ref.vdwl), ("coul", got.coul, ref.coul)):
        if rel_error(a, b) > fe:
            bad.append(f"{label}: {name} = {a!r}, reference {b!r} "
                       f"(error {rel_error(a, b):.3g} > {fe:.3g})")
    if got.pe_sum is not None and rel_error(got.pe_sum, got.vdwl + got.coul) > fe:
        bad.append(f"{label}: sum of pe/atom {got.pe_sum!r} != pair energy {got.vdwl + got.coul!r}")
    return bad


def check(cfg, variant, res):
    """All failures of the stages of one variant of cfg."""
    bad = []
    for stage, factors in FACTORS[variant].items():
        bad += compare(res[stage], cfg.reference(REFERENCE[stage]), cfg.epsilon, factors,
                       f"{cfg.path.name} {variant} {stage}")
    return bad


# ---------------------------------------------------------------------------------------------
# the tests
# ---------------------------------------------------------------------------------------------

def installed_styles():
    """Every word of `lmp -h` (its lists of styles among them)."""
    out = subprocess.run([lmp_path(), "-h"], capture_output=True, text=True, timeout=60).stdout
    return set(out.split())


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """Configs (regenerated first under SALTDEM_FORCE_YAML_GENERATE), styles, cached runs."""
    base = tmp_path_factory.mktemp("force-styles")
    if GENERATE:
        for path in CASES:
            generate(path, base / f"generate-{path.stem}")
    configs = {p.name: Config(p) for p in CASES}
    runs = {}

    def job(name, variant):
        restart = None
        if variant == "restart":
            runs[name, "plain"].result()
            restart = base / name / "plain" / "init.restart"
        return run_variant(configs[name], variant, base / name / variant, restart)

    # every run started at once, JOBS at a time (lmp mostly waits for MPI to start); the restart
    # runs, which read the plain runs' files, last
    with ThreadPoolExecutor(max_workers=JOBS) as pool:
        for variant in sorted(FACTORS, key=lambda v: v == "restart"):
            for name in configs:
                runs[name, variant] = pool.submit(job, name, variant)
        yield {"configs": configs, "styles": installed_styles(),
               "get": lambda name, variant: runs[name, variant].result()}


@pytest.mark.parametrize("variant", list(FACTORS))
@pytest.mark.parametrize("name", [p.name for p in CASES])
def test_force_style(session, name, variant):
    """The YAML's deck, run as `variant`, gives its reference energies, virial and forces."""
    cfg = session["configs"][name]
    if variant in cfg.skip:
        pytest.skip(f"{variant} in skip_tests")
    suffix = "/omp" if variant.startswith("omp") else ""
    missing = [f"{kind} {style}" for kind, style in cfg.prerequisites
               if (style + suffix if kind == "pair" else style) not in session["styles"]]
    if missing:
        pytest.skip(f"not in this lmp: {', '.join(missing)}")
    bad = check(cfg, variant, session["get"](name, variant))
    assert not bad, "\n".join(bad[:20]) + (f"\n... {len(bad)} in all" if len(bad) > 20 else "")


def test_cases_cover_the_styles():
    """Both styles, both viscous laws, and both as sub-styles of pair hybrid have a YAML."""
    styles = [Config(p) for p in CASES]
    text = [(c.pair_style.split(), " ".join(c.pair_coeff)) for c in styles]
    assert any(s[0] == "saltdem/cohesive" for s, _ in text)
    for law in ("fluid", "contact"):
        assert any(s[0] == "saltdem/viscous" and law in c for s, c in text), law
    hybrid = [(s, c) for s, c in text if s[0] == "hybrid"]
    assert any("saltdem/cohesive" in s and "saltdem/viscous" in s and "fluid" in c
               and "contact" in c for s, c in hybrid)


ALTERED = "atomic-pair-saltdem_cohesive.yaml"    # the YAML the two tests below alter


def test_comparison_fails_on_an_altered_reference(session, tmp_path):
    """A copy of a YAML with one reference force changed in its 10th digit, or one stress
    component, fails the comparison with the unchanged run; the unaltered copy passes."""
    name = ALTERED
    res = session["get"](name, "plain")
    copy = tmp_path / name
    text = (HERE / name).read_text()
    copy.write_text(text)
    assert check(Config(copy), "plain", res) == []
    cfg = Config(copy)
    fx = cfg.reference("run").forces[7][0]
    old = f"{fx:23.16e}"
    assert text.count(old) == 1
    copy.write_text(text.replace(old, f"{fx * (1 + 1e-10):23.16e}"))
    bad = check(Config(copy), "plain", res)
    assert len(bad) == 1 and "run: fx of atom 7" in bad[0], bad
    sxy = cfg.reference("init").stress[3]
    copy.write_text(text.replace(f"{sxy:23.16e}", f"{-sxy:23.16e}", 1))
    bad = check(Config(copy), "plain", res)
    assert any("init: stress xy" in b for b in bad), bad


def test_comparison_fails_on_an_altered_coefficient(tmp_path):
    """A copy of a YAML whose first pair_coeff has its first coefficient larger by 1e-9 runs to
    other forces than its reference: the comparison fails at init and after the steps."""
    cfg = Config(HERE / ALTERED)
    first = cfg.pair_coeff[0].split()
    k = next(i for i, w in enumerate(first) if i >= 2 and is_number(w))
    first[k] = repr(float(first[k]) * (1 + 1e-9))
    res = results(run(fresh_deck(cfg, coeffs=[" ".join(first), *cfg.pair_coeff[1:]]), tmp_path),
                  ["init", "run"])
    bad = check(cfg, "plain", res)
    assert any(" init: f" in b for b in bad) and any(" run: f" in b for b in bad), bad


# pair_style keywords whose values only bound the time step
STEP_ONLY = {"dtfactor", "viscfactor"}


def perturbed(cfg):
    """(label, pair_style, pair_coeff) for every nonzero number of the pair setup that enters
    the forces, made 1 % larger (an integer: one larger; the contact law's gap, a cutoff, 0).
    Not: the time-step factors, and K of a fluid pair I != J (the pressure is the type's)."""
    out = []

    def bump(words, k):
        if words[k - 1] == "contact":
            return "0"
        return str(int(words[k]) + 1) if words[k].isdigit() else repr(float(words[k]) * 1.01)

    def numbers(words, start):
        cross_k = (len(words) > 2 and "*" not in words[0] + words[1] and words[0] != words[1]
                   and "fluid" in words)
        return [k for k in range(start, len(words)) if words[k - 1] not in STEP_ONLY
                and is_number(words[k]) and float(words[k]) != 0.0
                and not (cross_k and k == words.index("fluid") + 2)]

    style = cfg.pair_style.split()
    for k in numbers(style, 1):
        out.append((f"pair_style {style[k - 1]} {style[k]}",
                    " ".join(style[:k] + [bump(style, k)] + style[k + 1:]), cfg.pair_coeff))
    for n, line in enumerate(cfg.pair_coeff):
        w = line.split()
        for k in numbers(w, 2):
            coeffs = list(cfg.pair_coeff)
            coeffs[n] = " ".join(w[:k] + [bump(w, k)] + w[k + 1:])
            out.append((f"pair_coeff {line!r} word {k} ({w[k]})", cfg.pair_style, coeffs))
    return out


def is_number(w):
    try:
        float(w)
    except ValueError:
        return False
    return True


@pytest.mark.parametrize("name", [p.name for p in CASES])
def test_every_coefficient_acts(name, tmp_path):
    """Every coefficient of the YAML's pair setup changes its forces (one lmp, a stage per
    coefficient): the deck puts every term of the laws to work, so the reference checks them
    all."""
    cfg = Config(HERE / name)
    cases = perturbed(cfg)
    r = run("\nclear\n".join(fresh_deck(cfg, style, coeffs, f"s{k}_", restart=False)
                             for k, (_, style, coeffs) in enumerate(cases)), tmp_path)
    res = results(r, [f"s{k}_{s}" for k in range(len(cases)) for s in ("init", "run")])
    idle = []
    for k, (label, _, _) in enumerate(cases):
        moved = max(rel_error(a, b) for s in ("init", "run")
                    for i, f in cfg.reference(s).forces.items()
                    for a, b in zip(res[f"s{k}_{s}"].forces[i], f))
        if moved < 1e-6:
            idle.append(f"{label}: forces change by at most {moved:.3g}")
    assert not idle, "\n".join(idle)


if __name__ == "__main__":
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        for arg in sys.argv[1:] or [str(p) for p in CASES]:
            generate(arg, pathlib.Path(d) / pathlib.Path(arg).stem)
            print("generated", arg)
