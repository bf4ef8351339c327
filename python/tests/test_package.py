"""The package's shape (issue 38, the Python tools like fmpy's): every package folder has an
`__init__.py`; the command lines alone parse arguments (argparse only in the `cli.py`
modules); every public function and method of `hybeam` is annotated (its parameters and its
return; mypy, run by scripts/test.sh, checks the annotations); the console scripts name
functions that exist."""

import ast
import importlib
import pathlib

import pytest
import tomllib

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "hybeam"
PYPROJECT = PACKAGE.parent / "pyproject.toml"


def _modules():
    return sorted(PACKAGE.rglob("*.py"))


def test_every_package_folder_has_an_init():
    folders = {p.parent for p in _modules()}
    assert folders, PACKAGE
    missing = [str(f) for f in folders if not (f / "__init__.py").exists()]
    assert not missing, missing


def test_argparse_only_in_the_cli_modules():
    users = [
        p.relative_to(PACKAGE).as_posix()
        for p in _modules()
        if "argparse" in p.read_text() and p.name != "cli.py"
    ]
    assert not users, users


def _public_functions(tree: ast.Module):
    """(qualified name, node) of the functions not starting with `_` at module level and
    the methods of classes not starting with `_` (nested functions are not public)."""
    for node in tree.body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            if not node.name.startswith("_"):
                yield node.name, node
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            for item in node.body:
                if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef) and (
                    not item.name.startswith("_") or item.name == "__init__"
                ):
                    yield f"{node.name}.{item.name}", item


def test_every_public_function_is_annotated():
    missing = []
    for path in _modules():
        tree = ast.parse(path.read_text())
        for name, fn in _public_functions(tree):
            args = fn.args.posonlyargs + fn.args.args + fn.args.kwonlyargs
            args += [a for a in (fn.args.vararg, fn.args.kwarg) if a is not None]
            bare = [a.arg for a in args if a.annotation is None and a.arg not in ("self", "cls")]
            if bare or (fn.returns is None and fn.name != "__init__"):
                where = f"{path.relative_to(PACKAGE).as_posix()}:{fn.lineno} {name}"
                missing.append(f"{where} ({', '.join(bare) or 'return'})")
    assert not missing, "\n".join(missing)


@pytest.mark.parametrize(
    "script", sorted(tomllib.loads(PYPROJECT.read_text())["project"]["scripts"].items())
)
def test_the_console_scripts_name_cli_functions(script):
    name, target = script
    module, _, function = target.partition(":")
    assert module.endswith(".cli"), (name, target)
    assert callable(getattr(importlib.import_module(module), function)), (name, target)
