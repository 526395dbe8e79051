"""The library's layers import downwards only.

    base → catalog → llm (plumbing) → language → scenes → study
         → sim → policies / serving → rollout → report → pipeline → cli

A module may import its own layer and any layer below it; an import that
climbs (``language`` importing ``scenes``, or the simulator importing a
policy) fails this test with the module and the import named.
Lazy imports inside functions and ``TYPE_CHECKING`` imports count too: they
are dependencies all the same.
"""

from __future__ import annotations

from ladev_lib.fingerprint import PACKAGE_ROOT, imported_modules, module_file, package_modules

LAYERS: tuple[frozenset[str], ...] = (
    frozenset({"", "arrays", "errors", "registry", "store", "tables", "config", "fingerprint", "seeding", "vocabulary"}),
    frozenset({"catalog", "assets"}),
    frozenset({"llm"}),
    frozenset({"language"}),
    frozenset({"scenes"}),
    frozenset({"study"}),
    frozenset({"sim"}),
    frozenset({"policies", "serving"}),
    frozenset({"rollout"}),
    frozenset({"report"}),
    frozenset({"pipeline"}),
    frozenset({"cli"}),
)


def _unit(module: str) -> str:
    """The top-level package (or base module) of ``module`` below ``ladev_lib``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _layer(module: str) -> int:
    unit = _unit(module)
    for i, layer in enumerate(LAYERS):
        if unit in layer:
            return i
    raise AssertionError(f"{module}: package {unit!r} has no layer; add it to LAYERS")


def climbs() -> list[str]:
    out = []
    for module in package_modules("ladev_lib"):
        path = module_file(module)
        assert path is not None
        for imported in sorted(imported_modules(module, path)):
            if _layer(imported) > _layer(module):
                out.append(f"{module} imports {imported}")
    return out


def test_every_package_has_a_layer() -> None:
    units = {p.stem if p.is_file() else p.name for p in PACKAGE_ROOT.iterdir()
             if (p.suffix == ".py" and p.stem != "__init__") or (p / "__init__.py").is_file()}
    for unit in units:
        _layer(f"ladev_lib.{unit}")


def test_no_import_climbs_a_layer() -> None:
    found = climbs()
    assert not found, "imports that climb the layers:\n" + "\n".join(found)


def test_the_walk_sees_lazy_imports() -> None:
    # The CLI reaches every layer, lazily inside its commands: the walk must see that.
    cli = {_unit(m) for m in imported_modules("ladev_lib.cli.run", module_file("ladev_lib.cli.run"))}
    assert cli - {"cli"}, cli
