"""Sphinx configuration of ActiveGrain's manual.

Built as LAMMPS builds its own manual, with Debian 12's python3-sphinx and python3-myst-parser
(for the Markdown pages); CI builds it with warnings as errors:

    python3 -m sphinx -W -b html docs build/docs-html

Style pages keep LAMMPS's format. Links to LAMMPS's own pages use the role
:lammps:`fix gravity <fix_gravity>` (an external link to docs.lammps.org); links between our
pages use :doc:. ``.. code-block:: LAMMPS`` is highlighted by the small lexer below.
"""
import os

from pygments.lexer import RegexLexer, bygroups
from pygments.token import Comment, Keyword, Name, Number, String, Text

project = "ActiveGrain"
author = "the ActiveGrain developers"
copyright = "the ActiveGrain developers"

extensions = ["sphinx.ext.mathjax", "sphinx.ext.extlinks", "myst_parser"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "figures/**/*.txt"]

# LAMMPS's manual, one page per command: :lammps:`fix gravity <fix_gravity>`.
extlinks = {"lammps": ("https://docs.lammps.org/%s.html", "%s")}

# Markdown pages: headings get the anchors GitHub gives them (validation.md#the-full-size-channel).
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

# Equations offline: Debian's libjs-mathjax (MathJax 2, tools/debian-packages) where it is
# installed, else Sphinx's default, MathJax 3 from a CDN. MathJax 2 typesets only the elements
# Sphinx and myst mark as math (class "math"), not $ or \( met elsewhere in the text; myst's own
# settings for that are MathJax 3's, and would hide the Markdown pages' equations from MathJax 2.
MATHJAX_LOCAL = "/usr/share/javascript/mathjax/MathJax.js"
if os.path.isfile(MATHJAX_LOCAL):
    mathjax_path = f"file://{MATHJAX_LOCAL}?config=TeX-AMS-MML_HTMLorMML"
    mathjax2_config = {"tex2jax": {"inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]],
                                   "processEscapes": False, "processEnvironments": False,
                                   "processRefs": False, "ignoreClass": "document",
                                   "processClass": "math"}}
    myst_update_mathjax = False

html_theme = "alabaster"
html_theme_options = {"nosidebar": False, "page_width": "1100px"}
# activegrain.css: literal blocks (the style pages' syntax blocks) wrap to the page, as in
# LAMMPS's manual.
html_static_path = ["_static"]
html_css_files = ["activegrain.css"]
html_show_sourcelink = False
pygments_style = "default"
highlight_language = "none"


class LAMMPSLexer(RegexLexer):
    """Input decks: the command at the start of a line, comments, variables, numbers."""

    name = "LAMMPS"
    aliases = ["lammps"]
    filenames = ["in.*"]

    tokens = {
        "root": [
            (r"\s*#.*?$", Comment),
            (r"^(\s*)([a-z_][a-z0-9_/]*)", bygroups(Text, Keyword)),
            (r"\$\{[^}]*\}|\$\([^)]*\)|\$[A-Za-z]", Name.Variable),
            (r"\b[vcf]_[A-Za-z0-9_\[\]]+", Name.Variable),
            (r'"[^"]*"|\'[^\']*\'', String),
            (r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\b", Number),
            (r"&\s*$", Text),
            (r"\S+", Text),
            (r"\s+", Text),
        ],
    }


def setup(app):
    app.add_lexer("LAMMPS", LAMMPSLexer)
