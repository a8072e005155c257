"""Sphinx extension: the API reference documents each object once, and references find it.

The API reference (``api/``) documents every object once, in the module that defines it
(``fdsc.synthesis.synthesize``), so that its entry and its highlighted source agree: an
``automodule`` skips the functions and classes its module's ``__all__`` re-exports from a
public sibling (autodoc documents every name of ``__all__``, so ``fdsc.paper.reproduced.stationary``
would describe ``StationaryRuns`` a second time and a type reference to it would be ambiguous). Readers and
docstrings also name objects the way they are imported: ``fdsc.synthesize`` (the package's
re-export), ``fdsc.paper.reproduced.stationary.stationary_runs`` (a chapter module re-exporting
a sibling's function) or a bare ``Band`` inside another module's docstring. When the Python
domain finds no target for such a name, this extension imports the object it names and resolves
the reference to the object's defining module and qualified name instead. A name that imports
nothing, or whose object is not documented, stays unresolved as before (plain text).

Highlighted source pages (``sphinx.ext.viewcode``) are made for the library's modules only: the
paper layer's modules (``fdsc.paper``, about half of the code) get no ``[source]`` link, which
halves the build's 30 s of highlighting; their source is in the repository and each chapter's
notebook can be downloaded.
"""

import importlib

from sphinx.ext.autodoc import ModuleDocumenter

_ROOT = "fdsc"


def _lookup(path):
    """The object ``path`` names, walking attributes from the top package (lazy re-exports
    included) and importing submodules on the way; ``None`` if it names nothing."""
    parts = path.split(".")
    if parts[0] != _ROOT:
        return None
    try:
        obj = importlib.import_module(_ROOT)
    except ImportError:
        return None
    for i, part in enumerate(parts[1:], start=1):
        try:
            obj = getattr(obj, part)
        except AttributeError:
            try:
                obj = importlib.import_module(".".join(parts[: i + 1]))
            except ImportError:
                return None
    return obj


def _defined_at(obj):
    """``module.qualname`` of a function, class or method; ``None`` for data and modules."""
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    if not isinstance(module, str) or not isinstance(qualname, str) or "<" in qualname:
        return None
    return f"{module}.{qualname}"


def _defined_in(obj, modname):
    """Whether ``modname`` is where ``obj`` is documented: the module that defines it, or the
    public module that re-exports it from a private one (``fdsc._grid_run.shift_signal`` is
    ``fdsc.prepared.shift_signal``). Data, which has no ``__module__``, is documented where
    ``__all__`` lists it."""
    module = getattr(obj, "__module__", None)
    if not isinstance(module, str) or module == modname:
        return True
    return any(part.startswith("_") for part in module.split("."))


class DefinedHereDocumenter(ModuleDocumenter):
    """``automodule`` that documents, of the names in ``__all__``, those :func:`_defined_in`
    places in this module (autodoc documents every name of ``__all__``, imported or not)."""

    def get_object_members(self, want_all):
        check_module, members = super().get_object_members(want_all)
        if want_all and self.__all__ is not None:
            members = [m for m in members if _defined_in(m.object, self.modname)]
        return check_module, members


def _exported_from(name):
    """``fdsc.X.rest`` as ``fdsc.<module>.X.rest``, with the module the package's export table
    names for ``X`` (for data, which carries no ``__module__``, and names defined in a private
    module); ``None`` for any other name."""
    parts = name.split(".")
    if len(parts) < 2 or parts[0] != _ROOT:
        return None
    module = getattr(importlib.import_module(_ROOT), "_WHERE", {}).get(parts[1])
    return None if module is None else ".".join([_ROOT, module, *parts[1:]])


def _candidates(target, node):
    """Fully qualified names a Python reference may mean: as written, in the current module,
    and as a name of the package (``Band`` read as ``fdsc.Band``)."""
    names = [target] if target.startswith(_ROOT + ".") else []
    module = node.get("py:module")
    if module and not target.startswith(_ROOT + "."):
        names.append(f"{module}.{target}")
    if not target.startswith(_ROOT + "."):
        names.append(f"{_ROOT}.{target}")
    return names


def _resolve(app, env, node, contnode):
    if node.get("refdomain") != "py" or node.get("refspecific"):
        return None
    target = node.get("reftarget", "")
    domain = env.get_domain("py")
    for name in _candidates(target, node):
        for where in (_defined_at(_lookup(name)), _exported_from(name)):
            if where is None or where == target:
                continue
            found = domain.resolve_xref(env, node["refdoc"], app.builder, node["reftype"], where,
                                        node, contnode)
            if found is not None:
                return found
    return None


def _is_paper(modname):
    return modname == "fdsc.paper" or modname.startswith("fdsc.paper.")


def _library_source_only(app, modname):
    """``viewcode-find-source``: no source (and so no ``[source]`` link) for the paper layer."""
    return ("", {}) if _is_paper(modname) else None


def _no_paper_source_pages(app, env):
    """``env-updated``: viewcode makes no page for a module whose entry is False."""
    modules = getattr(env, "_viewcode_modules", {})
    for modname in [m for m in modules if _is_paper(m)]:
        modules[modname] = False


def setup(app):
    app.setup_extension("sphinx.ext.autodoc")
    app.connect("viewcode-find-source", _library_source_only)
    app.connect("env-updated", _no_paper_source_pages)
    app.add_autodocumenter(DefinedHereDocumenter, override=True)
    app.connect("missing-reference", _resolve)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
