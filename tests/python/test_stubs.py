"""The type stub (client/python/tessera/__init__.pyi) names what the module
has: every exported name, every method and property of its classes, and
each function's parameters in order, as pybind11 states them in the first
line of the docstring. A binding added without its stub, or a stub whose
arguments drift from the binding's, fails here."""

import ast
import pathlib
import re

import tessera

STUB = pathlib.Path(__file__).resolve().parents[2] / "client" / "python" / "tessera" / "__init__.pyi"
ALIASES = {"ElementId", "VertexIds", "Vec3", "PathLike"}


def stub_tree():
    return ast.parse(STUB.read_text())


def stub_parameters(function):
    a = function.args
    names = [p.arg for p in a.posonlyargs + a.args]
    if a.kwonlyargs:
        names += ["*"] + [p.arg for p in a.kwonlyargs]
    return [n for n in names if n != "self"]


def bound_parameters(obj):
    """None for an overloaded function, whose stub states the union."""
    first = (obj.__doc__ or "").splitlines()[0]
    if "(*args, **kwargs)" in first:
        return None
    inside = first[first.index("(") + 1 : first.rindex(")")]
    return [n for n in re.findall(r"(?:^|, )(\*|\w+)(?=: |, |$)", inside) if n != "self"]


def test_the_stub_names_every_export():
    names = {n.name for n in stub_tree().body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert names == set(tessera.__all__)


def test_every_stub_function_has_the_bindings_parameters():
    checked = 0
    for node in stub_tree().body:
        if isinstance(node, ast.FunctionDef):
            bound = bound_parameters(getattr(tessera, node.name))
            assert bound is None or stub_parameters(node) == bound, node.name
            checked += 1
        if not isinstance(node, ast.ClassDef):
            continue
        cls = getattr(tessera, node.name)
        for member in node.body:
            if not isinstance(member, ast.FunctionDef) or member.name.startswith("__"):
                continue
            bound = getattr(cls, member.name)
            is_property = any(isinstance(d, ast.Name) and d.id == "property" for d in member.decorator_list)
            if is_property or isinstance(bound, property):
                continue
            assert stub_parameters(member) == bound_parameters(bound), f"{node.name}.{member.name}"
            checked += 1
    assert checked > 50


def test_every_bound_method_is_in_the_stub():
    for node in stub_tree().body:
        if not isinstance(node, ast.ClassDef):
            continue
        cls = getattr(tessera, node.name)
        if issubclass(cls, BaseException):
            continue  # the exceptions' attributes are set on raising
        stubbed = {m.name for m in node.body if isinstance(m, ast.FunctionDef)}
        public = {n for n in dir(cls) if not n.startswith("_")}
        assert public <= stubbed, f"{node.name}: {sorted(public - stubbed)}"
