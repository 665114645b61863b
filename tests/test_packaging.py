"""The package's declared optional dependencies and the set-up that CI runs agree: every
requirement of every extra in pyproject.toml is installed by scripts/setup.sh, so that under CI
no test skips for a missing package (tests/optional_packages.py fails there instead)."""

from __future__ import annotations

import pathlib
import re
import shlex
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _setup_requirements() -> set[str]:
    text = (ROOT / "scripts" / "setup.sh").read_text()
    # The pip install command, with its continuation lines joined.
    joined = re.sub(r"\\\n\s*", " ", text)
    (line,) = [ln for ln in joined.splitlines() if "pip install -q" in ln and "maturin" in ln]
    return {w for w in shlex.split(line) if re.match(r"^[A-Za-z0-9_.-]+[<>=]", w)}


@pytest.mark.skipif(sys.version_info < (3, 11), reason="tomllib needs Python 3.11")
def test_setup_installs_every_extra():
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    installed = _setup_requirements()
    missing = {f"{extra}: {req}" for extra, reqs in extras.items() for req in reqs if req not in installed}
    assert not missing, f"scripts/setup.sh does not install {sorted(missing)}"
    assert "metrics" in extras and "flip-evaluator>=1.7" in extras["metrics"]


def test_no_source_comment_cites_a_tracker_number():
    # Comments say why in words a reader can follow; a tracker number is not something a reader
    # of the code can open. (A docs section title quoted with its page is a citation of the docs.)
    pattern = re.compile(r"\bissues? \d+", re.IGNORECASE)
    cited = []
    for folder, suffixes in (("crates", {".rs"}), ("wgsl", {".wgsl"}), ("python", {".py", ".pyi"}), ("tests", {".py"})):
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix not in suffixes or "target" in path.parts:
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                if pattern.search(line) and "docs/" not in line:
                    cited.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert not cited, "\n".join(cited)


def test_no_code_outside_the_registry_classifies_methods_by_name():
    """What a method is (stochastic, a ground truth, what it makes, which options it takes) comes
    from the registry (`vsgl.method_info`, `vsgl.method_options`), so a new method needs no edit
    elsewhere. A membership test against method names (`method in ("vpl", "vsgl")`) or a
    constant that collects them is a second list that falls behind; rendering a method by name
    and default selections (`--methods vpl,vsgl`) are not lists of what methods are."""
    import vsgl

    names = "|".join(vsgl.METHODS)
    quoted = rf'"(?:{names})"'
    collection = rf"[(\[{{]\s*{quoted}(?:\s*,\s*{quoted})*\s*,?\s*[)\]}}]"
    patterns = [re.compile(rf"\bin\s*{collection}"), re.compile(rf"^\s*[A-Z][A-Z0-9_]*\s*(?::[^=]*)?=\s*{collection}"),
                # A table keyed by method names (per-method settings, tolerances): a row per method by hand.
                re.compile(rf"(?:^\s*|[{{,]\s*){quoted}\s*:")]
    found = []
    for path in sorted([*(ROOT / "python").rglob("*.py"), *(ROOT / "scripts").rglob("*.py")]):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if any(p.search(line) for p in patterns):
                found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert not found, "\n".join(found)
    # The check can fail: the sweep's old list of random methods, planted, is found.
    assert patterns[1].search('STOCHASTIC = {"vpl", "vsgl"}') and patterns[0].search('if m in ("vpl", "vsgl"):')
    assert patterns[2].search('FLIP_FRACTION = {"pathtrace": 0.01}') and patterns[2].search('    "vsgl2": {"rsm_size": 48},')


# Repository paths as the docs cite them: from the repository root, starting with a top-level
# folder of the repository (or a root file), e.g. `experiments/lavapipe/corpus/truth.txt`.
_REPO_PATH = re.compile(
    r"(?<![\w./-])((?:docs|experiments|scripts|tests|crates|python|wgsl|\.ci)/[\w.{},*/-]*[\w*}/]"
    r"|(?:README|CHANGELOG)\.md|LICENSE-(?:MIT|APACHE)|pyproject\.toml|Cargo\.toml)"
)
_MD_LINK = re.compile(r"\]\(([^)\s#]+)(?:#[^)]*)?\)")


def _expand_braces(path: str) -> list[str]:
    m = re.search(r"\{([^{}]*)\}", path)
    if not m:
        return [path]
    return [p for alt in m.group(1).split(",") for p in _expand_braces(path[: m.start()] + alt + path[m.end() :])]


def _cited_paths_missing(text: str, page: pathlib.Path) -> list[str]:
    missing = []
    for target in _MD_LINK.findall(text):  # links: relative to the page
        if re.match(r"^[a-z]+:", target):
            continue
        if not (page.parent / target).exists():
            missing.append(f"link {target}")
    for match in _REPO_PATH.finditer(text):  # paths in text: from the repository root
        cited = match.group(1)
        if text[match.end() : match.end() + 1] == "<" or re.search(r"\b[A-Z]{3,}\b", cited):
            continue  # a pattern to fill in (`gpu_<name>.sh`, `corpus/NAME.json`), not a file
        for path in _expand_braces(cited.rstrip("/.")):
            if "*" in path:
                if not list(ROOT.glob(path)):
                    missing.append(path)
            elif not (ROOT / path).exists():
                missing.append(path)
    return missing


def test_every_repository_path_the_docs_cite_exists():
    # A moved or renamed file must take its citations along: the README, the user guide and the
    # experiment pages name scripts and result files a reader is meant to open or run.
    pages = [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted((ROOT / "docs").rglob("*.md")),
             *sorted((ROOT / "experiments").glob("*.md"))]
    missing = [f"{page.relative_to(ROOT)}: {m}" for page in pages for m in _cited_paths_missing(page.read_text(), page)]
    assert not missing, "\n".join(missing)
