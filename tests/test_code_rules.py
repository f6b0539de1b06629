"""LAMMPS's rules for the package's source files (doc/src/Modify_style.rst of the LAMMPS source):
licence and author header in every file, style headers that include only their base class,
no OpenMP code outside the *_omp files (those are built with the OPENMP package only), and the
files formatted with LAMMPS's .clang-format (src/.clang-format)."""
import pathlib
import re
import shutil
import subprocess

import pytest

from lmprun import ROOT

PKG = ROOT / "src" / "USER-SALTDEM"


def package_files():
    """The package's tracked source files (files in progress, not yet in git, are left out)."""
    out = subprocess.run(["git", "ls-files", "src/USER-SALTDEM"], cwd=ROOT, capture_output=True,
                         text=True, check=True).stdout.split()
    files = [ROOT / f for f in out if f.endswith((".h", ".cpp"))]
    assert len(files) > 20, files
    return files


STYLE = re.compile(r"^(Pair|Fix|Command|Compute)Style\(", re.M)


def test_licence_and_author_header():
    for f in package_files():
        head = f.read_text()[:1500]
        assert "LAMMPS development team: developers@lammps.org" in head, f.name
        assert "GNU General Public License" in head, f.name
        assert "Contributing author" in head, f.name


def test_style_headers_include_only_their_base_class():
    """A style header includes the header of its base class(es) and nothing else, uses no
    'using' statements, and declares no law or loop bodies (those live in saltdem_pair_loop.h
    and the law headers, which only .cpp files include)."""
    seen = 0
    for f in package_files():
        if f.suffix != ".h":
            continue
        text = f.read_text()
        if not STYLE.search(text):
            continue
        seen += 1
        bases = re.findall(r"class \w+ : (.+?) \{", text.replace("\n", " "))
        assert bases, f.name
        includes = re.findall(r'^#include [<"](.+?)[">]', text, re.M)
        base_headers = {
            "Pair": "pair.h", "Fix": "fix.h", "Command": "command.h",
            "PairSaltdem": "pair_saltdem.h", "PairSaltdemCohesive": "pair_saltdem_cohesive.h",
            "PairSaltdemViscous": "pair_saltdem_viscous.h", "PairSaltdemOMP": "pair_saltdem_omp.h",
            "FixSaltdemMotion": "fix_saltdem_motion.h", "FixSaltdemNVE": "fix_saltdem_nve.h"}
        want = {base_headers[b.split()[-1]] for b in bases[0].split(",")}
        assert set(includes) == want, (f.name, includes, want)
        assert not re.search(r"^\s*using ", text, re.M), f.name
    assert seen >= 14
    # the base class headers the styles include follow the same rule
    for name, allowed in [("pair_saltdem.h", {"pair.h"}), ("pair_saltdem_omp.h", {"thr_omp.h"}),
                          ("fix_saltdem_motion.h", {"fix.h"})]:
        includes = re.findall(r'^#include [<"](.+?)[">]', (PKG / name).read_text(), re.M)
        assert set(includes) == allowed, (name, includes)
    # the shared loop knows no concrete style: each law is a policy it is handed, defined in
    # the style's law header; only .cpp files include the loop and the law headers
    loop = (PKG / "saltdem_pair_loop.h").read_text()
    assert "PairSaltdem::loop(" in loop
    assert not re.search(r"PairSaltdem(Cohesive|Viscous)|_law\.h", loop)
    for law, name in [("saltdem_cohesive_law.h", "CohesiveLaw"),
                      ("saltdem_viscous_law.h", "ViscousLaw")]:
        assert f"struct {name}" in (PKG / law).read_text(), law
    for f in package_files():
        if f.suffix == ".h" and f.name != "saltdem_pair_loop.h":
            text = f.read_text()
            assert '#include "saltdem_pair_loop.h"' not in text, f.name
            assert not re.search(r'#include "saltdem_\w+_law\.h"', text), f.name


OMP = re.compile(r"#pragma omp|[<\"]omp\.h[>\"]|omp_compat\.h|_OPENMP|comm->nthreads|Suffix::OMP|"
                 r"\"thr_omp\.h\"|\bThrOMP\b")


def test_openmp_code_only_in_omp_files():
    """The OpenMP variants have their own *_omp.{h,cpp} (built with the OPENMP package only),
    and every line of OpenMP code is there: thread bounds, per-thread sums, pragmas."""
    omp = [f for f in package_files() if f.stem.endswith("_omp")]
    assert {f.name for f in omp} >= {
        "pair_saltdem_cohesive_omp.h", "pair_saltdem_cohesive_omp.cpp",
        "pair_saltdem_viscous_omp.h", "pair_saltdem_viscous_omp.cpp", "fix_saltdem_nve_omp.h",
        "fix_saltdem_nve_omp.cpp", "pair_saltdem_omp.h"}
    for f in package_files():
        if f.stem.endswith("_omp"):
            continue
        bad = [line for line in f.read_text().splitlines() if OMP.search(line)]
        assert not bad, (f.name, bad)


FORMATTED_WITH = "14"    # the clang-format major version the files were formatted with


def test_clang_format():
    """The files are formatted with LAMMPS's .clang-format (src/.clang-format, a copy of the
    LAMMPS source's src/.clang-format).  Other clang-format versions format some constructs
    differently: the check runs with the version the files were formatted with."""
    exe = shutil.which("clang-format")
    if exe is None:
        pytest.skip("clang-format is not installed")
    version = re.search(r"version (\d+)", subprocess.run([exe, "--version"], capture_output=True,
                                                          text=True).stdout)
    if not version or version.group(1) != FORMATTED_WITH:
        pytest.skip(f"clang-format {version.group(1) if version else '?'}: the files were "
                    f"formatted with version {FORMATTED_WITH}")
    assert (ROOT / "src" / ".clang-format").read_text().startswith("---\nLanguage:")
    files = [str(f) for f in package_files()]
    r = subprocess.run([exe, "--dry-run", "--Werror", *files], cwd=ROOT, capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr[-3000:]


# ---- the repository: no large files in git, user docs as LAMMPS's doc rules ask ----

MAX_TRACKED_BYTES = 1 << 20    # 1 MB: run data (restarts, dumps) lives outside git


def tracked_files():
    """The repository's tracked files (relative paths), or a skip outside a git checkout."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    r = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"not a git checkout: {r.stderr.strip()[:200]}")
    return [f for f in r.stdout.split("\0") if f]


def oversized(sizes, limit=MAX_TRACKED_BYTES):
    """The (path, bytes) pairs over the limit, largest first."""
    return sorted(((f, n) for f, n in sizes if n > limit), key=lambda fn: -fn[1])


def test_no_tracked_file_over_1mb():
    """Every tracked file is at most 1 MB: restart files and dumps of long runs are kept outside
    git (bench/segments/README.md says where and how to regenerate them)."""
    files = tracked_files()
    assert files
    sizes = [(f, (ROOT / f).stat().st_size) for f in files if (ROOT / f).is_file()]
    big = oversized(sizes)
    assert not big, (f"{len(big)} tracked file(s) over {MAX_TRACKED_BYTES} bytes: "
                     + ", ".join(f"{f} ({n} bytes)" for f, n in big))


# the user pages: what a user reads (the logs of how a number came about are in docs/notes/)
def user_pages():
    return sorted([*ROOT.glob("docs/*.md"), *ROOT.glob("docs/*.rst"), ROOT / "README.md",
                   ROOT / "examples" / "README.md"])


ISSUE_NUMBER = re.compile(r"\bissues? #?\d+|(?<![\w&/])#\d+\b|\(issue\b", re.I)


def issue_numbers(text):
    """Lines that cite an issue ('issue 16', 'issues 16 and 18', '#16'), outside code blocks,
    inline code and link targets."""
    bad, code = [], False
    for k, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith(("```", "~~~")):
            code = not code
            continue
        if code:
            continue
        prose = re.sub(r"\]\([^)]*\)", "]", re.sub(r"`[^`]*`", "", line))    # no link targets
        if ISSUE_NUMBER.search(prose):
            bad.append(f"{k}: {line.strip()[:100]}")
    return bad


def test_user_pages_cite_no_issue_numbers():
    """A user page says what is, not which issue made it so (the history is in docs/notes/)."""
    pages = user_pages()
    assert len(pages) > 15
    bad = {p.relative_to(ROOT).as_posix(): b for p in pages if (b := issue_numbers(p.read_text()))}
    assert not bad, bad


# British spellings LAMMPS's docs do not use (American English); whole words, any case
BRITISH = ("behaviour", "behaviours", "modelling", "modelled", "colour", "colours", "centre",
           "centres", "centred", "metre", "metres", "neighbour", "neighbours", "neighbouring",
           "neighbourhood", "licence",
           "favour", "analyse", "analysed", "normalise", "normalised", "initialise", "initialised",
           "discretisation", "localised", "localisation", "optimise", "optimised", "recognise",
           "minimise", "minimised", "parametrised", "parameterised", "stabilise", "organise",
           "grey", "labelled", "travelled", "cancelled")
BRITISH_RE = re.compile(r"\b(" + "|".join(BRITISH) + r")\b", re.I)


def rst_problems(text):
    """Non-ASCII characters and British spellings in a .rst page, as 'line: what'."""
    bad = []
    for k, line in enumerate(text.splitlines(), 1):
        odd = sorted({c for c in line if ord(c) > 127})
        if odd:
            bad.append(f"{k}: non-ASCII {''.join(odd)!r}")
        bad += [f"{k}: British '{m}'" for m in BRITISH_RE.findall(line)]
    return bad


def test_rst_pages_are_ascii_and_american():
    """The style pages (docs/*.rst) follow LAMMPS's doc rules: ASCII only, American English."""
    pages = sorted(ROOT.glob("docs/*.rst"))
    assert len(pages) >= 10
    bad = {p.name: b for p in pages if (b := rst_problems(p.read_text()))}
    assert not bad, bad


LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def prose_lines(text):
    """(line number, line) outside code blocks, inline code removed."""
    code = False
    for k, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith(("```", "~~~")):
            code = not code
            continue
        if not code:
            yield k, re.sub(r"`[^`]*`", "", line)


def heading_anchors(text):
    """The anchors GitHub gives a page's headings (lower case, punctuation dropped, spaces to
    hyphens, -1, -2, ... for repeats)."""
    out, seen = set(), {}
    for _, line in prose_lines(text.replace("`", "")):
        m = re.match(r"#{1,6} (.*)", line)
        if m:
            slug = re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-")
            n = seen.get(slug, 0)
            seen[slug] = n + 1
            out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def broken_links(page):
    """The relative links and images of a markdown page whose file or heading does not exist."""
    bad = []
    for k, line in prose_lines(page.read_text()):
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):
                continue
            path, _, frag = target.partition("#")
            dest = (page.parent / path).resolve() if path else page
            if not dest.exists():
                bad.append(f"{k}: {target} (no such file)")
            elif frag and dest.suffix == ".md" and frag not in heading_anchors(dest.read_text()):
                bad.append(f"{k}: {target} (no such heading)")
    return bad


def test_docs_links_resolve():
    """Every relative link and image of the markdown docs points at a file that exists, and at a
    heading of it where it names one.  docs/gallery/intro.md is a part of
    docs/gallery.md (tools/docs/gallery_page.py puts them there) and use its links."""
    parts = {"intro.md"}
    pages = [p for p in ROOT.glob("docs/**/*.md") if not (p.parent.name == "gallery" and p.name in parts)]
    pages += [ROOT / "README.md", ROOT / "examples" / "README.md", *ROOT.glob("bench/**/README.md")]
    assert len(pages) > 10
    bad = {p.relative_to(ROOT).as_posix(): b for p in pages if (b := broken_links(p))}
    assert not bad, bad
