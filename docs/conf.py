"""Sphinx configuration of the frictionsim documentation site (built by scripts/docs into out/docs/).

The API reference is generated from the *installed* frictionsim (autosummary + numpydoc; the engine's classes
carry their pybind11 docstrings), the Markdown notes are read with myst-parser and the gallery
(examples/gallery/*.py) is run by sphinx-gallery on every build, so a stale example fails the build.
docs/build.py builds from a staged copy of docs/, README.md and examples/gallery/, so nothing is written into
the source tree; this file finds the repository from its own location in either place.
"""

from __future__ import annotations

import importlib
import inspect
import os
import re
import sys
import warnings
from pathlib import Path

import frictionsim
from sphinx.ext import autosummary

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent  # the repository, or docs/build.py's staged copy of it
sys.path.insert(0, str(DOCS / "_ext"))

project = "frictionsim"
author = "the frictionsim authors"
copyright = "the frictionsim authors"  # noqa: A001 (Sphinx's name)
release = frictionsim.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "plain_docstrings",  # docs/_ext: the docstrings' plain-text formulas shown as written
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = ["_build", "_ext", "build.py", "gallery/*.ipynb", "gallery/*.py", "gallery/*.zip", "**.md5"]
html_theme = "alabaster"
html_title = f"frictionsim {release}"
html_static_path: list = []
html_theme_options = {
    "description": "Friction-driven dynamics in drilling: a header-only C++17 engine with Python bindings",
    "fixed_sidebar": False,
    "page_width": "1260px",
    "sidebar_width": "240px",
    "body_max_width": "none",  # alabaster caps the text at 800 px: the examples' code and tables need more
}
html_show_sourcelink = False

# -- API reference: autosummary over the installed module, numpydoc for the docstrings -----------------------
autosummary_generate = True
autosummary_ignore_module_all = False  # a module's page lists its __all__, re-exports included
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "groupwise"
autodoc_typehints = "none"  # the signature shows them; numpydoc's "Parameters" say the rest
autodoc_inherit_docstrings = True
numpydoc_show_class_members = False  # the class template lists members itself
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set = set()  # the docstrings' prose is checked by review, not by a lint here
numpydoc_xref_param_type = False


def _api_modules() -> list:
    """The modules api.rst documents, in its order."""
    return re.findall(r"^\s+(frictionsim(?:\.\w+)*)\s*$", (DOCS / "api.rst").read_text(encoding="utf-8"), re.M)


def _reexports() -> dict:
    """module -> {name: page}: the classes and functions a module re-exports (``frictionsim.wells.DrillString``
    is ``frictionsim.DrillString``) get one page, the first module of api.rst that lists them; the others link
    to it. Documenting an object twice would describe its canonical name (``frictionsim._core.DrillString``)
    twice."""
    home, links = {}, {}
    for modname in _api_modules():
        module = importlib.import_module(modname)
        links[modname] = {}
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if not (inspect.isclass(obj) or inspect.isroutine(obj)):
                continue
            if id(obj) in home:
                links[modname][name] = home[id(obj)]
            else:
                home[id(obj)] = f"{modname}.{name}"
    return links


autosummary_context = {"reexports": _reexports()}
# A module's table shows each member's first sentence: the papers' "Fig. 7", "eq. 6" do not end it.
autosummary.WELL_KNOWN_ABBREVIATIONS = tuple(sorted(set(autosummary.WELL_KNOWN_ABBREVIATIONS)
                                                    | {"Fig.", "Figs.", "eq.", "eqs.", "Eq.", "cf.", "No."}))
# numpydoc also parses a docstring for the signature, before _ext/plain_docstrings has renamed the bindings'
# "Keywords" and "Conditions" sections for the page: that early look has nothing to report.
warnings.filterwarnings("ignore", message="Unknown section", category=UserWarning)

# -- Markdown (docs/*.md, README's quick start) ---------------------------------------------------------------
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3
# Code blocks without a language (the architecture's tree, shell output) are shown as plain text.
highlight_language = "none"

# -- Gallery: examples/gallery/*.py, run on every build -------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",  # every plot_*.py is executed
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "show_memory": False,
    "min_reported_time": 0,
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "thumbnail_size": (320, 224),
    "within_subsection_order": "FileNameSortKey",
    "capture_repr": (),  # what the examples print is shown, not the repr of a cell's last Artist
}

# The figures of an example are what the docs test checks in Chromium; keep them crisp but small.
os.environ.setdefault("MPLBACKEND", "agg")
sys.dont_write_bytecode = True  # no __pycache__ beside the staged examples
