"""Every public function and class of both layers documents exactly its parameters (numpydoc).

Modelled on python-control's ``control/tests/docstrings_test.py``, with three differences: there is
no list of exceptions (a public name either documents its parameters or the test fails), a name
documented under ``Parameters`` that is not a parameter fails too (stale documentation), and a case
is one (module, object) pair, so that a failure names the function and what it lacks.

What is checked, for every public module of :mod:`fdsc` and :mod:`fdsc.paper` (no dotted component
starting with an underscore; ``__main__`` counts as public):

* the module has a docstring and an ``__all__`` whose names all exist;
* every function or class named in ``__all__`` and defined in that module has a docstring;
* its signature's parameters (for a class: those of ``__init__``, generated from the fields for a
  dataclass; ``self``/``cls`` excluded) are the names listed in the docstring's ``Parameters`` (or
  ``Other Parameters``) section, ``*args``/``**kwargs`` with their stars, several names on one line
  allowed (``P, Q : (n, n) array_like``);
* the same for every public method a class defines (plain, class and static methods, and
  ``__call__``); a property needs a docstring only.

A ``__main__`` module that runs at import (a top-level ``sys.exit``) cannot be imported by a test;
its docstring is read from the source instead.
"""

import ast
import dataclasses
import functools
import importlib
import importlib.util
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import fdsc

_RULE = re.compile(r"^\s*-{3,}\s*$")
_PARAMETER_SECTIONS = ("Parameters", "Other Parameters")


# -- the checker ------------------------------------------------------------------------------------

def documented_parameters(doc):
    """Names listed in the ``Parameters`` and ``Other Parameters`` sections of a numpydoc docstring.

    A name line starts in the first column of the (dedented) docstring; its names are what precedes
    ``" : "``, split at commas. Indented lines are descriptions.
    """
    lines = inspect.cleandoc(doc or "").splitlines()
    names, inside = [], False
    for k, line in enumerate(lines):
        if k + 1 < len(lines) and line.strip() and _RULE.match(lines[k + 1]):
            inside = line.strip() in _PARAMETER_SECTIONS
        elif inside and line.strip() and not line[0].isspace() and not _RULE.match(line):
            names += [n.strip() for n in line.split(" : ", 1)[0].split(",")]
    return names


def signature_parameters(func, *, bound):
    """Parameter names of ``func`` as numpydoc lists them (``*args``, ``**kwargs``); ``bound``
    drops the first parameter (``self`` or ``cls``)."""
    params = list(inspect.signature(func).parameters.values())
    if bound:
        params = params[1:]
    stars = {inspect.Parameter.VAR_POSITIONAL: "*", inspect.Parameter.VAR_KEYWORD: "**"}
    return [stars.get(p.kind, "") + p.name for p in params]


def _has_doc(doc):
    return doc is not None and doc.strip() != ""


def _class_doc(cls):
    """The class docstring, or None when there is none (a dataclass makes one up from its fields)."""
    doc = cls.__doc__
    if dataclasses.is_dataclass(cls) and doc and doc.startswith(f"{cls.__name__}(") and "\n" not in doc:
        return None
    return doc


def _compare(where, func, docs, *, bound):
    expected = signature_parameters(func, bound=bound)
    documented = [n for d in docs for n in documented_parameters(d)]
    found = [f"{where}: parameter {n!r} is not documented" for n in expected if n not in documented]
    found += [f"{where}: documents {n!r}, which is not a parameter" for n in documented
              if n not in expected]
    found += [f"{where}: documents {n!r} twice" for n in sorted(set(documented))
              if documented.count(n) > 1]
    return found


def _function_problems(func, where, *, bound=False):
    if not _has_doc(func.__doc__):
        return [f"{where}: no docstring"]
    return _compare(where, func, [func.__doc__], bound=bound)


def _python_init(cls):
    """The ``__init__`` that constructs ``cls`` if written in Python (None for a built-in one,
    such as ``Exception.__init__``, whose generic ``*args`` nobody documents)."""
    for klass in cls.__mro__:
        if "__init__" in vars(klass):
            init = vars(klass)["__init__"]
            return init if inspect.isfunction(init) else None
    return None


def _class_problems(cls, where):
    doc = _class_doc(cls)
    found = [] if _has_doc(doc) else [f"{where}: no docstring"]
    init = _python_init(cls)
    if init is None:
        found += [f"{where}: documents {n!r}, which is not a parameter"
                  for n in documented_parameters(doc)]
    else:
        found += _compare(where, init, [doc, init.__doc__], bound=True)
    for name, attr in vars(cls).items():
        if name.startswith("_") and name != "__call__":
            continue
        here = f"{where}.{name}"
        if isinstance(attr, property | functools.cached_property):
            getter = attr.fget if isinstance(attr, property) else attr.func
            if not _has_doc(getter.__doc__):
                found.append(f"{here}: no docstring")
        elif isinstance(attr, classmethod | staticmethod):
            found += _function_problems(attr.__func__, here, bound=isinstance(attr, classmethod))
        elif inspect.isfunction(attr):
            found += _function_problems(attr, here, bound=True)
    return found


def problems(obj, where):
    """What the docstrings of a public function or class lack, one message per problem."""
    if inspect.isclass(obj):
        return _class_problems(obj, where)
    return _function_problems(obj, where)


# -- the modules and objects ------------------------------------------------------------------------

def _is_main_guard(node):
    """True for ``if __name__ == "__main__":``."""
    t = node.test if isinstance(node, ast.If) else None
    return (isinstance(t, ast.Compare) and isinstance(t.left, ast.Name) and t.left.id == "__name__"
            and any(isinstance(c, ast.Constant) and c.value == "__main__" for c in t.comparators))


def exits_on_import(source):
    """True if module source calls ``sys.exit``/``exit`` or raises ``SystemExit`` when imported
    (outside functions, classes and an ``if __name__ == "__main__":`` block)."""
    pending = list(ast.parse(source).body)
    while pending:
        node = pending.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef | ast.Lambda) \
                or _is_main_guard(node):
            continue
        if isinstance(node, ast.Call):
            f = node.func
            if (isinstance(f, ast.Attribute) and f.attr == "exit" and isinstance(f.value, ast.Name)
                    and f.value.id == "sys") or (isinstance(f, ast.Name) and f.id in ("exit", "SystemExit")):
                return True
        pending += list(ast.iter_child_nodes(node))
    return False


def _public(name):
    return all(part == "__main__" or not part.startswith("_") for part in name.split("."))


def _public_modules():
    """``{name: (module or None, source path, import error or None)}`` of both layers."""
    names = ["fdsc"] + [m.name for m in pkgutil.walk_packages(fdsc.__path__, "fdsc.")]
    out = {}
    for name in sorted(n for n in names if _public(n)):
        path = Path(importlib.util.find_spec(name).origin)
        if exits_on_import(path.read_text(encoding="utf-8")):
            out[name] = (None, path, None)
            continue
        try:
            out[name] = (importlib.import_module(name), path, None)
        except Exception as exc:  # reported by the module's own case, not at collection
            out[name] = (None, path, f"{type(exc).__name__}: {exc}")
    return out


MODULES = _public_modules()


def _defined_here(module, name):
    obj = getattr(module, name, None)
    return (inspect.isclass(obj) or callable(obj)) and getattr(obj, "__module__", None) == module.__name__


CASES = [(mod_name, name) for mod_name, (module, _, _) in MODULES.items() if module is not None
         for name in getattr(module, "__all__", ()) if _defined_here(module, name)]


# -- the tests --------------------------------------------------------------------------------------

def test_the_walk_covers_both_layers():
    # guards the parametrized tests below against checking nothing
    assert {"fdsc", "fdsc.bands", "fdsc.design", "fdsc.__main__", "fdsc.paper",
            "fdsc.paper.shared.results", "fdsc.paper.__main__"} <= set(MODULES)
    assert not any(part.startswith("_") and part != "__main__"
                   for name in MODULES for part in name.split("."))
    assert MODULES["fdsc.paper.__main__"][0] is None and MODULES["fdsc.__main__"][0] is not None
    layers = {name.split(".")[1] == "paper" for name, _ in CASES}
    assert layers == {False, True} and len(CASES) > 100


@pytest.mark.parametrize("mod_name", sorted(MODULES))
def test_module_has_a_docstring_and_all(mod_name):
    module, path, error = MODULES[mod_name]
    assert error is None, f"{mod_name} does not import: {error}"
    if module is None:  # runs at import: read the docstring from the source
        assert ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))), f"{mod_name}: no docstring"
        return
    assert _has_doc(module.__doc__), f"{mod_name}: no module docstring"
    assert hasattr(module, "__all__"), f"{mod_name}: no __all__"
    missing = [n for n in module.__all__ if not hasattr(module, n)]
    assert missing == [], f"{mod_name}: __all__ names {missing}, which the module does not define"


@pytest.mark.parametrize(("mod_name", "name"), CASES, ids=[f"{m}.{n}" for m, n in CASES])
def test_public_object_documents_its_parameters(mod_name, name):
    found = problems(getattr(MODULES[mod_name][0], name), f"{mod_name}.{name}")
    assert found == [], "\n".join(found)


# -- the checker can fail ---------------------------------------------------------------------------

def _documented(a, b, *args, scale=1.0, **options):
    """Sum of numbers.

    Parameters
    ----------
    a, b : float
        Two numbers on one line.
    *args : float
        More numbers.
    scale : float, optional
        Factor.
    **options
        Ignored.
    """


def _undocumented(a, b, *args, scale=1.0):
    """Sum of numbers.

    Parameters
    ----------
    a : float
    args : float
        Without its star.
    c : float
        No such parameter.

    Returns
    -------
    scale : float
        A name under Returns is not a parameter.
    """


def _no_docstring(a):
    pass


@dataclasses.dataclass(frozen=True)
class _Spec:
    """A rectangle.

    Parameters
    ----------
    width : float
        Width.
    """

    width: float
    height: float

    @classmethod
    def square(cls, side):
        """A square.

        Parameters
        ----------
        side : float
            Side.
        """
        return cls(side, side)

    def area(self, scale):
        """Area."""
        return scale * self.width * self.height

    @property
    def ratio(self):
        return self.width / self.height


@dataclasses.dataclass(frozen=True)
class _NoDoc:
    width: float


def test_checker_parses_numpydoc_parameters():
    assert documented_parameters(_documented.__doc__) == ["a", "b", "*args", "scale", "**options"]
    assert documented_parameters(_undocumented.__doc__) == ["a", "args", "c"]
    assert documented_parameters(None) == []


def test_checker_accepts_a_documented_function():
    assert problems(_documented, "_documented") == []


def test_checker_reports_missing_stale_and_absent_docs():
    assert problems(_undocumented, "f") == [
        "f: parameter 'b' is not documented",
        "f: parameter '*args' is not documented",
        "f: parameter 'scale' is not documented",
        "f: documents 'args', which is not a parameter",
        "f: documents 'c', which is not a parameter",
    ]
    assert problems(_no_docstring, "g") == ["g: no docstring"]


def test_checker_reads_a_dataclass_init_its_methods_and_properties():
    assert problems(_Spec, "S") == [
        "S: parameter 'height' is not documented",
        "S.area: parameter 'scale' is not documented",
        "S.ratio: no docstring",
    ]
    assert problems(_NoDoc, "N") == ["N: no docstring", "N: parameter 'width' is not documented"]


@pytest.mark.parametrize(("source", "exits"), [
    ("import sys\nfrom .cli import main\nsys.exit(main())\n", True),
    ("raise SystemExit(main())\n", True),
    ("import atexit\nlog.exit('ok')\n", False),
    ("import sys\ndef main():\n    sys.exit(0)\nif __name__ == '__main__':\n    sys.exit(main())\n", False),
])
def test_checker_recognizes_a_module_that_exits_on_import(source, exits):
    assert exits_on_import(source) is exits
