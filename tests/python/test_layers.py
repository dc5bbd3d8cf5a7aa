"""The package is in layers, and a module imports only from its own layer or
those below it (the order is in camlink/__init__.py's docstring)."""

from __future__ import annotations

import ast
import importlib
import inspect
import warnings
from pathlib import Path

import pytest

import camlink

PACKAGE = Path(camlink.__file__).resolve().parent

#: Layers from the bottom up; a module's layer is the first prefix it matches.
LAYERS: list[tuple[str, tuple[str, ...]]] = [
    (
        "base",
        (
            "camlink._core",
            "camlink.errors",
            "camlink.warn",
            "camlink.signals",
            "camlink.progress",
            "camlink.settings",
            "camlink.records",
            "camlink.units",
        ),
    ),
    ("io", ("camlink.io",)),
    ("model", ("camlink.model", "camlink.results", "camlink.builder")),
    ("viz", ("camlink.viz",)),
    ("cam", ("camlink.cam",)),
    ("machine", ("camlink.machine",)),
    ("synth", ("camlink.synth",)),
    ("study", ("camlink.study",)),
    # The package's own namespace re-exports the public names of the layers
    # below; the command line is written against it.
    ("facade", ("camlink",)),
    # The editor in the browser, written against the public API.
    ("studio", ("camlink.studio",)),
    ("cli", ("camlink.cli", "camlink.__main__")),
]

#: Imports that run up the layers on purpose: the model API's convenience
#: methods hand over to the pictures (`Model.draw`, `Results.plot`, the
#: notebook displays). Each is inside the method, so importing the model API
#: loads no picture code; and each is listed here, so a new one is a decision.
HAND_OVERS = {
    ("camlink.model", "camlink.viz.drawing"),
    ("camlink.model", "camlink.viz.notebook"),
    ("camlink.results", "camlink.viz.plots"),
    ("camlink.results", "camlink.viz.drawing"),
    ("camlink.results", "camlink.viz.animate"),
    ("camlink.results", "camlink.viz.viewer"),
    ("camlink.results", "camlink.viz.notebook"),
}


def layer(module: str) -> int:
    for rank, (_, prefixes) in enumerate(LAYERS):
        if any(module == p or module.startswith(p + ".") for p in prefixes):
            return rank
    raise AssertionError(f"{module} is in no layer: add it to LAYERS")


def module_name(path: Path) -> str:
    parts = ["camlink", *path.relative_to(PACKAGE).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path: Path) -> list[tuple[str, int]]:
    """Every camlink module `path` imports, with its line (type-checking
    imports included: they name a dependency too)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = module_name(path) if path.name == "__init__.py" else module_name(path).rpartition(".")[0]
    found: list[tuple[str, int]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(a.name, node.lineno) for a in node.names if a.name.startswith("camlink")]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                target = f"{base}.{node.module}" if node.module else base
            else:
                target = node.module or ""
            if not target.startswith("camlink"):
                continue
            for alias in node.names:
                # `from camlink.cli import cam` imports the module camlink.cli.cam.
                sub = f"{target}.{alias.name}"
                found.append((sub if (PACKAGE / Path(*sub.split(".")[1:])).exists()
                              or (PACKAGE / (str(Path(*sub.split(".")[1:])) + ".py")).exists()
                              or sub == "camlink._core" else target, node.lineno))
    return found


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))


def test_every_module_is_in_a_layer() -> None:
    assert len(MODULES) > 30
    for path in MODULES:
        layer(module_name(path))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_imports_run_down_the_layers(path: Path) -> None:
    me = module_name(path)
    up = [
        f"line {line}: {target} ({LAYERS[layer(target)][0]}) from {me} ({LAYERS[layer(me)][0]})"
        for target, line in imports(path)
        if layer(target) > layer(me) and (me, target) not in HAND_OVERS
    ]
    assert not up, "imports running up the layers:\n" + "\n".join(up)


def test_the_check_sees_an_upward_import(tmp_path: Path) -> None:
    # The checker itself: a base module importing the pictures is caught.
    fake = PACKAGE / "units.py"
    tree = imports(fake)
    assert all(layer(t) <= layer("camlink.units") for t, _ in tree)
    assert layer("camlink.viz.drawing") > layer("camlink.model") > layer("camlink.io.output")
    assert layer("camlink.cli.cam") > layer("camlink.study.runner") > layer("camlink.cam.design")


def test_old_module_names_still_import_and_warn() -> None:
    import importlib
    import sys

    for old, new in camlink.MOVED_MODULES.items():
        sys.modules.pop(old, None)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            module = importlib.import_module(old)
        assert module is importlib.import_module(new), old
        assert any(issubclass(w.category, DeprecationWarning) and new in str(w.message) for w in caught), old


def test_dir_lists_the_public_names() -> None:
    names = dir(camlink)
    for name in ("draw", "plot", "sweep", "load", "Model", "Results", "viz", "cam", "io", "study", "synth"):
        assert name in names, name
    assert "sys" not in names and "importlib" not in names


@pytest.mark.parametrize(
    "module",
    [
        "camlink.cam.design",
        "camlink.cam.export",
        "camlink.cam.jump",
        "camlink.cam.plots",
        "camlink.cam.sizing",
        "camlink.cam.timing",
        "camlink.io",
        "camlink.io.model_form",
        "camlink.io.output",
        "camlink.io.results_file",
        "camlink.io.simengine2d",
    ],
)
def test_issue28_subpackage_modules_list_their_public_names(module: str) -> None:
    # Each module says what is public: its __all__ names exist, and every
    # public function or class defined in it is listed.
    mod = importlib.import_module(module)
    listed = set(mod.__all__)
    assert all(hasattr(mod, name) for name in listed), module
    defined = {
        name
        for name, value in vars(mod).items()
        if not name.startswith("_")
        and (inspect.isfunction(value) or inspect.isclass(value))
        and value.__module__ == module
    }
    assert defined <= listed, f"{module}: not in __all__: {sorted(defined - listed)}"


def test_issue28_cam_design_errors_are_model_errors(tmp_path: Path) -> None:
    # One exception hierarchy: every bad input is a camlink.ModelError.
    from camlink.cam.design import CamDesignError

    assert issubclass(CamDesignError, camlink.ModelError)
    bad = tmp_path / "bad_design.toml"
    bad.write_text("name = [\n")
    with pytest.raises(camlink.ModelError, match=r"bad_design\.toml"):
        camlink.cam.load(bad)
