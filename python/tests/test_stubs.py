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


# --- help() states the stub's types -------------------------------------------------------------------------

def flat_union(text: str) -> frozenset:
    """The members of a type annotation written as text: Optional[X] and Union[X, Y] flattened, the module path
    of the extension's classes (pybind11 prints raykernel._raykernel.Mesh) and of numpy.typing dropped."""
    text = text.replace("raykernel._raykernel.", "").replace("numpy.typing.", "npt.")

    def members(node) -> list:
        if isinstance(node, ast.Subscript) and ast.unparse(node.value) in ("Union", "Optional"):
            parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
            out = [m for p in parts for m in members(p)]
            return out + (["None"] if ast.unparse(node.value) == "Optional" else [])
        if isinstance(node, ast.Constant) and isinstance(node.value, str):  # a forward reference
            return members(ast.parse(node.value, mode="eval").body)
        return [ast.unparse(node)]

    return frozenset(members(ast.parse(text, mode="eval").body))


def extension_signature(f) -> tuple:
    """(name → annotation members, return members) from the first line of a pybind11 docstring."""
    first = f.__doc__.splitlines()[0]
    inside, returns = re.match(r"^\w+\((.*)\) -> (.*)$", first).groups()
    params: dict = {}
    depth, start = 0, 0
    pieces = []
    for i, ch in enumerate(inside + ","):  # split at the commas outside brackets
        depth += ch in "[(" 
        depth -= ch in "])"
        if ch == "," and depth == 0:
            pieces.append(inside[start:i].strip())
            start = i + 1
    for piece in pieces:
        if not piece or piece in ("*", "/"):
            continue
        name, annotation = piece.split(":", 1)
        if name == "self":
            continue
        # pybind11 names a std::vector argument List[...]; it takes any sequence, as the stub says
        params[name] = flat_union(annotation.split(" = ")[0].strip().replace("List[", "Sequence["))
    return params, flat_union(returns)


def stub_signatures(body) -> dict:
    """name → (parameter → annotation members, return members), the union over @overload variants."""
    out: dict = {}
    for node in body:
        if isinstance(node, ast.FunctionDef):
            params, returns = out.setdefault(node.name, ({}, set()))
            args = node.args
            for a in args.posonlyargs + args.args + args.kwonlyargs:
                if a.arg != "self" and a.annotation is not None:
                    params[a.arg] = params.get(a.arg, frozenset()) | flat_union(ast.unparse(a.annotation))
            if node.returns is not None:
                returns |= flat_union(ast.unparse(node.returns))
    return out


def test_help_shows_the_stub_types_not_handle():
    """help(raykernel.f) prints what the stub says each parameter and result is (pybind11 would print
    ``handle`` and ``object`` for the arguments the extension converts itself)."""
    tree = ast.parse(STUB.read_text())
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    scopes = [(_raykernel, tree.body), (_raykernel.testkit, classes["testkit"].body)]
    scopes += [(getattr(_raykernel, name), node.body) for name, node in classes.items()
               if name not in ("testkit", "InvalidInput", "MeshFileError", "MeshFileNotFoundError")]
    checked, wrong = 0, []
    for owner, body in scopes:
        for name, (params, returns) in stub_signatures(body).items():
            f = getattr(owner, name)
            if isinstance(f, property) or f.__doc__ is None or not f.__doc__.startswith(name + "("):
                continue  # properties, and the methods Python defines (the exception classes')
            shown, shown_returns = extension_signature(f)
            for param, members in params.items():
                if shown[param] != members or {"handle", "object"} & shown[param]:
                    wrong.append((name, param, sorted(shown[param]), sorted(members)))
            if returns and shown_returns != returns:
                wrong.append((name, "->", sorted(shown_returns), sorted(returns)))
            checked += 1
    assert not wrong, "\n".join(map(str, wrong))
    assert checked >= 60
