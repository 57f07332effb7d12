"""The manual: self-contained, every style page leads to a complete deck, the README's links into
docs/validation.md land on a heading. (tools/run-tests builds the site itself with Sphinx, -W.)"""
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = sorted([*ROOT.glob("docs/*.rst"), *ROOT.glob("docs/*.md"), ROOT / "bench" / "README.md",
                ROOT / "examples" / "README.md", *ROOT.glob("examples/*/README.md")])
STYLE_PAGES = [p for p in ROOT.glob("docs/*.rst") if re.search(r"^[^\n]+ command\n=+$", p.read_text(), re.M)]


def github_slug(heading):
    """The anchor GitHub (and myst's heading anchors) give a Markdown heading."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_page_cites_nothing_outside_the_repository(page):
    text = page.read_text()
    assert not re.search(r"\bSPEC\b", text), "cites SPEC, which is not in the repository"
    links = re.findall(r"\]\(([^)#\s]+)[^)]*\)", text) + re.findall(r":download:`[^<`]*<([^>]+)>`", text)
    for target in links:
        if re.match(r"[a-z]+:", target):      # a URL
            continue
        path = (page.parent / target).resolve()
        assert path.is_relative_to(ROOT) and path.exists(), f"{target}: not a file of the repository"


def test_no_source_deck_or_log_cites_spec():
    """Code comments, decks and their logs name our own pages for the model, not a file we do not ship."""
    files = [f for pattern in ("src/**/*.h", "src/**/*.cpp", "tests/**/*.h", "tests/**/*.cpp", "examples/*/in.*",
                               "examples/*/log.*", "bench/in.*", "python/**/*.py")
             for f in ROOT.glob(pattern) if f.name != "log.lammps"]    # a run's own log, never committed
    assert len(files) > 50
    citing = [str(f.relative_to(ROOT)) for f in files if re.search(r"\bSPEC\b", f.read_text(errors="replace"))]
    assert not citing, f"cite SPEC: {citing}"


def test_style_pages_link_the_minimal_deck():
    assert len(STYLE_PAGES) >= 7
    for page in STYLE_PAGES:
        assert "examples/minimal/in.minimal" in page.read_text(), page.name
    assert (ROOT / "examples" / "minimal" / "in.minimal").is_file()


def test_every_page_is_in_the_toctree():
    index = (ROOT / "docs" / "index.rst").read_text()
    listed = set(re.findall(r"^   (\w+)$", index, re.M))
    pages = {p.stem for p in ROOT.glob("docs/*.rst")} | {p.stem for p in ROOT.glob("docs/*.md")}
    assert pages - {"index"} == listed


def test_readme_anchors_into_validation_exist():
    text = (ROOT / "docs" / "validation.md").read_text()
    anchors = {github_slug(h) for h in re.findall(r"^#+ (.*)$", text, re.M)}
    anchors |= set(re.findall(r'<a name="([^"]+)"></a>', text))
    linked = set(re.findall(r"docs/validation\.md#([\w-]+)", (ROOT / "README.md").read_text()))
    assert linked, "README.md links no section of docs/validation.md"
    assert linked <= anchors, f"README.md links missing anchors: {linked - anchors}"


def test_validation_sections_link_to_existing_anchors_and_figures():
    text = (ROOT / "docs" / "validation.md").read_text()
    anchors = {github_slug(h) for h in re.findall(r"^#+ (.*)$", text, re.M)}
    for target in re.findall(r"\]\(#([\w-]+)\)", text):
        assert target in anchors, target
    for figure in re.findall(r"\]\((figures/[^)]+)\)", text):
        assert (ROOT / "docs" / figure).is_file(), figure
