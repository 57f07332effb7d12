"""The manual: self-contained, every style page leads to a complete deck, the README's links into
docs/validation.md land on a heading; built (as tools/run-tests builds it, Sphinx with -W), its
equations use Debian's MathJax from its file, offline, and its syntax blocks wrap to the page."""
import html.parser
import pathlib
import re
import shutil
import subprocess
import sys

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


# --- the built site: equations and wide syntax blocks, offline ----------------------------------

MATHJAX = pathlib.Path("/usr/share/javascript/mathjax/MathJax.js")     # Debian's libjs-mathjax


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The manual built as tools/run-tests builds it (warnings are errors): {page name: HTML}."""
    out = tmp_path_factory.mktemp("docs-html")
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", "html",
                           str(ROOT / "docs"), str(out)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return out, {p.name: p.read_text() for p in out.glob("*.html")}


def math_pages(pages):
    return {name: text for name, text in pages.items() if 'class="math notranslate' in text}


def test_equations_use_the_local_mathjax(site):
    """Every page with equations loads Debian's MathJax from its file (tools/debian-packages has
    libjs-mathjax), configured to typeset what Sphinx marks as math; no page loads anything from
    the network."""
    assert MATHJAX.is_file(), f"{MATHJAX}: install Debian's libjs-mathjax (tools/debian-packages)"
    config = re.search(r"\?config=([\w-]+)", (ROOT / "docs" / "conf.py").read_text()).group(1)
    assert (MATHJAX.parent / "config" / f"{config}.js").is_file(), config
    _, pages = site
    pages_with_math = math_pages(pages)
    assert {"pair_gran_impulse.html", "compute_polar_rod.html", "model.html"} <= set(pages_with_math)
    for name, text in pages_with_math.items():
        scripts = re.findall(r'<script[^>]*\ssrc="([^"]*MathJax[^"]*)"', text)
        assert scripts == [f"file://{MATHJAX}?config={config}"], (name, scripts)
        assert '"processClass": "math"' in text, name
    for name, text in pages.items():
        remote = re.findall(r'<(?:script|link|img)[^>]*\s(?:src|href)="(https?:[^"]*)"', text)
        assert not remote, (name, remote)


def test_literal_blocks_wrap_to_the_page(site):
    """The style pages' syntax blocks (literal blocks, <pre>) wrap instead of running off the page."""
    out, pages = site
    css = (out / "_static" / "activegrain.css").read_text()
    rule = re.search(r"^pre\s*\{([^}]*)\}", css, re.M)
    assert rule and re.search(r"white-space:\s*pre-wrap", rule.group(1)), css
    for name, text in pages.items():
        assert '<link rel="stylesheet" type="text/css" href="_static/activegrain.css" />' in text, name
    assert "<pre>pair_style gran/impulse" in re.sub(r"<span[^>]*>|</span>", "", pages["pair_gran_impulse.html"])


class _TypesetMath(html.parser.HTMLParser):
    """In a page as a browser shows it: the elements Sphinx marks as math, those MathJax typeset
    (it leaves a math/tex script in each), and any text still holding TeX delimiters."""

    def __init__(self):
        super().__init__()
        self.math, self.typeset, self.raw, self.in_script = 0, 0, [], 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.in_script += tag == "script"
        self.typeset += tag == "script" and (a.get("type") or "").startswith("math/tex")
        self.math += tag in ("span", "div") and "math notranslate" in (a.get("class") or "")

    def handle_endtag(self, tag):
        self.in_script -= tag == "script"

    def handle_data(self, data):
        if not self.in_script and re.search(r"\\[()\[\]]", data):
            self.raw.append(data.strip()[:80])


def headless_browser():
    for name in ("chromium-headless-shell", "chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


@pytest.mark.skipif(headless_browser() is None, reason="no Chromium here (not needed otherwise: not installed by tools/)")
def test_no_page_shows_raw_tex_in_a_browser(site, tmp_path):
    """Where Chromium is installed: each page with equations, opened from its file with the network
    out of reach, shows every equation typeset by MathJax and no TeX source."""
    out, pages = site
    browser = headless_browser()
    for name in math_pages(pages):
        done = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--allow-file-access-from-files",
                               f"--user-data-dir={tmp_path / 'profile'}", "--proxy-server=127.0.0.1:9",
                               "--virtual-time-budget=20000", "--dump-dom", (out / name).as_uri()],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, (name, done.stderr[-2000:])
        seen = _TypesetMath()
        seen.feed(done.stdout)
        assert seen.math > 0 and seen.typeset == seen.math and not seen.raw, (name, seen.math, seen.typeset, seen.raw)
