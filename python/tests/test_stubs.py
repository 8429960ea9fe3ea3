"""The type stubs (raykernel/_raykernel.pyi) state what the extension has: the same names, and for each function
the same parameters in the same order (as pybind11 states them in the first line of each docstring)."""

import ast
import doctest
import pathlib
import re

import pytest

import raykernel
from raykernel import _raykernel

STUB = pathlib.Path(raykernel.__file__).with_name("_raykernel.pyi")


def stub_functions(body) -> dict:
    """name → parameter names (the union over @overload variants, in first-seen order)."""
    out: dict = {}
    for node in body:
        if isinstance(node, ast.FunctionDef):
            args = node.args
            names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs if a.arg != "self"]
            seen = out.setdefault(node.name, [])
            seen.extend(n for n in names if n not in seen)
    return out


def extension_parameters(f) -> list:
    first = f.__doc__.splitlines()[0]
    inside = re.match(r"^\w+\((.*)\) ->", first).group(1)
    return [m.group(1) for m in re.finditer(r"(?:^|, )(\w+):", inside) if m.group(1) != "self"]


def public(module) -> set:
    return {n for n in dir(module) if not n.startswith("_")}


def test_stub_names_and_parameters_are_the_extensions():
    tree = ast.parse(STUB.read_text())
    functions = stub_functions(tree.body)
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    constants = {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    extension = public(_raykernel) - {"testkit"}
    assert set(functions) | (set(classes) - {"testkit"}) | (constants - {"__version__"}) == extension
    for name, params in functions.items():
        assert extension_parameters(getattr(_raykernel, name)) == params, name
    for name, node in classes.items():
        if name in ("testkit", "InvalidInput", "MeshFileError", "MeshFileNotFoundError"):  # Python classes
            continue
        for method, params in stub_functions(node.body).items():
            is_property = any(isinstance(d, ast.Name) and d.id == "property" for n in node.body
                              if isinstance(n, ast.FunctionDef) and n.name == method for d in n.decorator_list)
            if is_property:
                assert isinstance(getattr(getattr(_raykernel, name), method), property), (name, method)
            else:
                assert extension_parameters(getattr(getattr(_raykernel, name), method)) == params, (name, method)
    testkit_stub = stub_functions(classes["testkit"].body)
    testkit_constants = {n.target.id for n in classes["testkit"].body if isinstance(n, ast.AnnAssign)}
    assert set(testkit_stub) | testkit_constants == public(_raykernel.testkit)
    for name, params in testkit_stub.items():
        assert extension_parameters(getattr(_raykernel.testkit, name)) == params, name


def test_the_package_exports_the_extension():
    assert set(raykernel.__all__) <= public(raykernel)
    assert public(_raykernel) - {"testkit"} <= set(raykernel.__all__)


def test_every_public_function_has_a_docstring():
    for name in raykernel.__all__:
        obj = getattr(raykernel, name)
        if callable(obj):
            doc = obj.__doc__ or ""
            assert len(doc.splitlines()) >= 2 or (isinstance(obj, type) and doc), name


def test_the_package_docstring_examples_run():
    failures, tried = doctest.testmod(raykernel, verbose=False)
    assert tried >= 2 and failures == 0


def test_dir_shows_only_the_api():
    import raykernel.testing
    import raykernel.testing.hypothesis as strategies

    shown = dir(raykernel)
    assert "_types" not in shown and "_raykernel" not in shown and "annotations" not in shown
    assert {"Mesh", "load_mesh", "nearest_hit_batch", "testing", "dask", "__version__"} <= set(shown)
    assert all(hasattr(raykernel, name) for name in raykernel.__all__)
    assert raykernel.testing is raykernel.__getattr__("testing")
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        raykernel.nonexistent
    hidden = {"np", "st", "Fraction", "SearchStrategy", "Optional", "annotations", "Plane", "_raykernel"}
    assert not hidden & set(dir(strategies)) and set(dir(strategies)) == set(strategies.__all__)
    assert all(hasattr(strategies, name) for name in strategies.__all__)
    namespace: dict = {}
    exec("from raykernel.testing.hypothesis import *", namespace)
    assert set(namespace) - {"__builtins__"} == set(strategies.__all__)
    assert "np" not in dir(raykernel.testing) and "hypothesis" in dir(raykernel.testing)
