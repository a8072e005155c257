"""Sphinx extension: a book that loads nothing from the web.

1. MathJax is served from the book's own static files, never from a CDN.
2. The Thebe launcher (live code through a remote kernel, disabled in ``_config.yml``) is removed:
   Jupyter Book adds sphinx-thebe regardless, and sphinx-thebe writes its inline script twice per
   page (a console error: ``THEBE_JS_URL`` declared twice) naming a CDN URL.

3. The Status column of MyST-NB's execution table (``{nb-exec-table}``, page 'environment')
   says ``ok`` / ``failed`` in words instead of the emoji ✅ / ❌, which a machine without an
   emoji font (such as the browser test's) draws as an empty box.

MathJax 3 comes from the PyPI package ``django-static-mathjax`` (it ships MathJax's ``es5``
build as plain files; Django itself is not needed). After an HTML build this extension copies
the single-file ``tex-svg-full.js`` component (TeX input with every extension, SVG output, so no
web fonts are loaded) and the few folders it may load on demand into ``_static/mathjax``;
``_config.yml`` points ``mathjax_path`` at it.
"""

import importlib.util
import shutil
from pathlib import Path

from docutils import nodes
from sphinx.errors import ExtensionError
from sphinx.transforms.post_transforms import SphinxPostTransform

BUNDLE = "tex-svg-full.js"
ON_DEMAND = ("a11y", "ui", "input/tex/extensions")


def mathjax_es5_dir():
    """Folder holding MathJax's es5 build inside the installed package."""
    spec = importlib.util.find_spec("mathjax")
    for loc in (spec.submodule_search_locations or []) if spec else []:
        d = Path(loc) / "static" / "mathjax" / "es5"
        if (d / BUNDLE).is_file():
            return d
    raise ExtensionError("offline_mathjax: MathJax files not found; install the pinned "
                         "django-static-mathjax package (pip install -r requirements.txt)")


def _copy_mathjax(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    src = mathjax_es5_dir()
    dst = Path(app.outdir) / "_static" / "mathjax"
    dst.mkdir(parents=True, exist_ok=True)
    shutil.copy2(src / BUNDLE, dst / BUNDLE)
    for sub in ON_DEMAND:
        shutil.copytree(src / sub, dst / sub, dirs_exist_ok=True)


def _check_path(app, config):
    if config.mathjax_path != f"mathjax/{BUNDLE}":
        raise ExtensionError(f"offline_mathjax: set sphinx.config.mathjax_path to "
                             f"'mathjax/{BUNDLE}' in _config.yml (found {config.mathjax_path!r})")


def _drop_thebe(app, pagename, templatename, context, doctree):
    scripts = context.get("script_files")
    if scripts is None:
        return
    keep = [s for s in scripts
            if "sphinx-thebe" not in (getattr(s, "filename", None) or str(s))
            and "THEBE_JS_URL" not in (getattr(s, "attributes", {}).get("body") or "")]
    scripts[:] = keep


#: The execution table's status symbols and the words that replace them.
STATUS_WORDS = {"✅": "ok", "❌": "failed"}


class StatusInWords(SphinxPostTransform):
    """Replace the execution table's status emoji by words (runs after MyST-NB has built the
    table, priority 8, and before the references are resolved, priority 10)."""

    default_priority = 9

    def run(self, **kwargs):
        for table in self.document.findall(nodes.table):
            for text in list(table.findall(nodes.Text)):
                word = STATUS_WORDS.get(text.astext().strip())
                if word is not None:
                    text.parent.replace(text, nodes.Text(word))


def setup(app):
    mathjax_es5_dir()  # fail at start-up, not after a long build
    app.connect("config-inited", _check_path)
    app.connect("html-page-context", _drop_thebe, priority=900)
    app.connect("build-finished", _copy_mathjax)
    app.add_post_transform(StatusInWords)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
