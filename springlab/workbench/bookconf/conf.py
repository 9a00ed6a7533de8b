"""Sphinx configuration of springlab's book (``build/site``), built by
:mod:`springlab.workbench.book` from the executed notebooks: myst-nb reads them without
running them (papermill is the executor), sphinx-book-theme lays them out, autodoc writes
the API reference. Everything is served from the site itself: MathJax, fonts, search."""

import os
import re

from springlab.workbench import prose
from springlab.workbench.book import MATHJAX_SCRIPT, short_name

project = "springlab"
author = "springlab"
copyright = "springlab contributors"  # noqa: A001
extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.viewcode", "sphinx.ext.mathjax"]
root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
suppress_warnings = ["mystnb.unknown_mime_type"]  # tqdm's widget bars: the text bar is shown instead

# myst-nb: render, never execute; stderr (progress bars) left out of the book
nb_execution_mode = "off"
nb_output_stderr = "remove"
nb_merge_streams = True
# a cell's Markdown output (springlab.tables.Table, the claims) is read as MyST, like the notebook's own
# Markdown cells: tables and $...$ math; myst-nb's default, CommonMark, has neither
nb_render_markdown_format = "myst"
nb_ipywidgets_js = {}  # no widget scripts from a CDN
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3

# a broken cross-reference is an error (make figures builds with -W), nitpicky: every
# springlab name a docstring or a type hint mentions must resolve; types from other packages
# (numpy, sympy, pathlib) are not linked, the book having no network to their docs
nitpicky = True
nitpick_ignore_regex = [(r"py:.*", r"(numpy|np|pathlib|sympy|concurrent|collections|typing)\b.*")]

autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "description"

# MathJax 3 from the django-static-mathjax package, copied to _static/mathjax by the builder
mathjax_path = f"mathjax/{MATHJAX_SCRIPT}"
mathjax3_config = {
    # the theme marks the page mathjax_ignore; MathJax typesets the elements Sphinx marks as math
    "options": {"processHtmlClass": "tex2jax_process|mathjax_process|math|output_area",
                "ignoreHtmlClass": "tex2jax_ignore|mathjax_ignore"},
    # \tag{23b} shows a paper's own equation number; \text{...} is set in the page's face
    "tex": {"tags": "none"},
    "svg": {"fontCache": "global", "mtextInheritFont": True},
}

html_theme = "sphinx_book_theme"
html_title = "springlab"
html_static_path = ["_static"]
html_css_files = ["springlab.css"]
html_last_updated_fmt = None
html_theme_options = {
    "show_toc_level": 2,
    "use_download_button": True,
    "use_fullscreen_button": False,
    "home_page_in_toc": True,
    "navigation_with_keys": False,
    "max_navbar_depth": 2,  # chapters and the API's packages; a page's own sections are on its right
    "collapse_navbar": True,
}
html_show_sourcelink = False
html_copy_source = True  # the download button: the executed notebook (the builder puts papermill's copy there)
html_sourcelink_suffix = ""

# the book names each paper a docstring cites by its key (before an equation's number, or "paper NNN's") by its
# authors and year, linked to its chapter (springlab.workbench.prose): the key stays in the code, the reader
# sees the name
CHAPTERS = dict(item.split("=", 1) for item in os.environ.get("SPRINGLAB_BOOK_CHAPTERS", "").split(";") if item)
NAMES = {key: (stem, short_name(stem)) for key, stem in CHAPTERS.items()}
_REST_KEPT = re.compile(r"``.*?``|:[\w:-]+:`[^`]*`|`[^`]*`")
"""reST a docstring's names stay out of: literals, roles, references."""


def _link_citations(app, what, name, obj, options, lines):
    for k, line in enumerate(lines):
        lines[k] = prose._outside(line, _REST_KEPT, lambda text: prose._rewrite(
            text, None, NAMES, set(), lambda key, shown: f":doc:`{shown} </{NAMES[key][0]}>`",
            lambda key, number, shown: shown))


_UNDERLINE = re.compile(r"\s*-{3,}\s*")
_BAR = re.compile(r"(``.*?``|`[^`]*`)|\|")


def _plain_text(app, what, name, obj, options, lines):
    """springlab's docstrings are read as text first (``help()``): ``|x|`` is a magnitude, not
    a substitution, and an underlined "References" is a heading of the docstring, not a section
    of the page (a rubric)."""
    k = 0
    while k < len(lines):
        if k + 1 < len(lines) and lines[k].strip() and _UNDERLINE.fullmatch(lines[k + 1]):
            indent = lines[k][: len(lines[k]) - len(lines[k].lstrip())]
            lines[k:k + 2] = [f"{indent}.. rubric:: {lines[k].strip()}", ""]
        row = lines[k].strip()
        if not (row.startswith("+-") or (row.startswith("|") and row.endswith("|") and row.count("|") > 2)):
            # a grid table's rows keep their bars
            lines[k] = _BAR.sub(lambda m: m.group(1) or r"\|", lines[k])
        k += 1


def _data_stays_home(app, modname, attribute):
    """viewcode takes a documented constant's source from its value's module: ``CITATION``
    (a compiled pattern) from ``re``, paper 004's ``ARM`` from the module of its class. A
    constant is defined where it is documented; classes and functions keep their own module."""
    import importlib
    import inspect

    obj = getattr(importlib.import_module(modname), attribute, None)
    if inspect.isclass(obj) or inspect.isroutine(obj) or inspect.ismodule(obj):
        return getattr(obj, "__module__", None) or modname
    return modname


def _number_figures(app, doctree):
    """Each chapter's figures numbered from 1 in their order on the page, as a paper numbers them: the
    caption a notebook gives a figure (myst-nb's cell metadata ``mystnb.figure``) begins "Figure k." """
    from docutils import nodes

    figures = [f for f in doctree.findall(nodes.figure) if any(isinstance(c, nodes.caption) for c in f.children)]
    for k, figure in enumerate(figures, 1):
        caption = next(c for c in figure.children if isinstance(c, nodes.caption))
        caption.insert(0, nodes.inline("", f"Figure {k}. ", classes=["caption-number"]))


def _glued_powers(app, doctree, docname):
    """Numbers glued into the prose in Python's exponent form ("1e-06") written as "1 × 10⁻⁶"
    (:func:`springlab.workbench.prose.powers_of_ten`): myst-nb's glue marks them ``pasted-text``."""
    from docutils import nodes

    for node in list(doctree.findall(nodes.inline)):
        if "pasted-text" in node.get("classes", ()):
            text = node.astext()
            written = prose.powers_of_ten(text)
            if written != text and len(node.children) == 1:
                node.replace(node.children[0], nodes.Text(written))


def setup(app):
    app.connect("doctree-resolved", _glued_powers)
    app.connect("doctree-read", _number_figures)
    app.connect("viewcode-follow-imported", _data_stays_home)
    app.connect("autodoc-process-docstring", _plain_text)
    app.connect("autodoc-process-docstring", _link_citations)
