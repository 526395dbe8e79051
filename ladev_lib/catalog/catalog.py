"""Load and query the object catalog (``objects.yaml`` beside this module).

The catalog is data: ids, names, sizes, colours, masses and capabilities of
every object LADEV can put in a scene, and where its mesh lives in a
ManiSkill-layout asset directory. Code never lists objects itself.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Literal

import yaml
from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from ladev_lib.vocabulary import ObjectSetName

Shape = Literal["box", "cylinder", "sphere", "capsule", "plate", "flat", "container"]

DEFAULT_CATALOG_PATH = Path(__file__).with_name("objects.yaml")

_MESH_DIRS = {
    "simpler": "data/tasks/bridge_v2_real2sim_dataset/custom/models",
    "ycb": "data/assets/mani_skill2_ycb/models",
}


def normalize_name(text: str) -> str:
    """Lower-case, unify hyphens/apostrophes/spaces: 'Coca-Cola  can' -> 'coca cola can'."""
    text = text.lower().replace("'", "").replace("’", "")
    text = re.sub(r"[-_/]", " ", text)
    return re.sub(r"\s+", " ", text).strip()


class MeshRef(BaseModel):
    """Where an object's real mesh lives in a ManiSkill-layout asset dir."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    source: ObjectSetName
    model: str
    upright_euler_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def directory(self, asset_dir: Path) -> Path:
        return Path(asset_dir) / _MESH_DIRS[self.source] / self.model


class CatalogObject(BaseModel):
    """One logical object. See the header of ``objects.yaml`` for each field."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    id: str
    set: ObjectSetName
    display_name: str
    synonyms: tuple[str, ...] = ()
    category: str
    shape: Shape
    size_m: tuple[float, float, float]
    color: tuple[float, float, float]
    mass_kg: float = Field(gt=0)
    graspable: bool
    support: bool
    container: bool
    mesh: MeshRef | None = None

    @field_validator("size_m")
    @classmethod
    def _positive_size(cls, v: tuple[float, float, float]) -> tuple[float, float, float]:
        if min(v) <= 0 or max(v) > 0.5:
            raise ValueError(f"size_m must be in (0, 0.5] m per axis, got {v}")
        return v

    @field_validator("color")
    @classmethod
    def _unit_color(cls, v: tuple[float, float, float]) -> tuple[float, float, float]:
        if not all(0.0 <= c <= 1.0 for c in v):
            raise ValueError(f"color components must be in [0, 1], got {v}")
        return v

    @property
    def names(self) -> tuple[str, ...]:
        """Display name first, then synonyms."""
        return (self.display_name, *self.synonyms)

    @property
    def footprint_radius_m(self) -> float:
        """Radius of the circle that covers the object's footprint on the table."""
        x, y, _ = self.size_m
        return float(0.5 * (x * x + y * y) ** 0.5)

    def mesh_dir(self, asset_dir: Path | None) -> Path | None:
        """The mesh directory when ``asset_dir`` holds this object's files, else None."""
        if asset_dir is None or self.mesh is None:
            return None
        d = self.mesh.directory(asset_dir)
        return d if (d / "collision.obj").exists() or (d / "collision.ply").exists() else None


class Catalog(BaseModel):
    """All objects, with lookups by id and by name."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    schema_version: Literal[1] = 1
    objects: tuple[CatalogObject, ...]

    @model_validator(mode="after")
    def _unique(self) -> Catalog:
        seen_ids: set[str] = set()
        seen_names: dict[str, str] = {}
        for obj in self.objects:
            if obj.id in seen_ids:
                raise ValueError(f"duplicate catalog id {obj.id!r}")
            seen_ids.add(obj.id)
            for name in obj.names:
                key = normalize_name(name)
                if key in seen_names and seen_names[key] != obj.id:
                    raise ValueError(
                        f"name {name!r} of {obj.id!r} is already a name of {seen_names[key]!r}"
                    )
                seen_names[key] = obj.id
        return self

    # -- lookups -------------------------------------------------------------
    @functools.cached_property
    def _by_id(self) -> dict[str, CatalogObject]:
        return {o.id: o for o in self.objects}

    @functools.cached_property
    def _by_name(self) -> dict[str, CatalogObject]:
        return {normalize_name(n): o for o in self.objects for n in o.names}

    def __len__(self) -> int:
        return len(self.objects)

    # pydantic's BaseModel.__iter__ yields (field, value) pairs; a catalog iterates its objects,
    # which is what every caller means by `for obj in catalog`. The override is deliberate.
    def __iter__(self) -> Iterator[CatalogObject]:  # type: ignore[override]
        return iter(self.objects)

    def __contains__(self, object_id: object) -> bool:
        return object_id in self._by_id

    def get(self, object_id: str) -> CatalogObject:
        """The object with this id; a KeyError names close ids when there is none."""
        try:
            return self._by_id[object_id]
        except KeyError:
            close = [i for i in self._by_id if object_id.lower() in i or i in object_id.lower()]
            hint = f"; did you mean {', '.join(close[:5])}?" if close else ""
            raise KeyError(f"unknown catalog object id {object_id!r}{hint}") from None

    def by_name(self, name: str) -> CatalogObject | None:
        """Exact match on a display name or synonym (case and punctuation ignored)."""
        return self._by_name.get(normalize_name(name))

    def ids(self) -> list[str]:
        return [o.id for o in self.objects]

    def select(
        self,
        *,
        sets: Iterable[ObjectSetName] | None = None,
        graspable: bool | None = None,
        support: bool | None = None,
        container: bool | None = None,
    ) -> list[CatalogObject]:
        """Objects matching every given filter, in catalog order."""
        wanted = set(sets) if sets is not None else None
        out = []
        for o in self.objects:
            if wanted is not None and o.set not in wanted:
                continue
            if graspable is not None and o.graspable != graspable:
                continue
            if support is not None and o.support != support:
                continue
            if container is not None and o.container != container:
                continue
            out.append(o)
        return out


def load_catalog(path: str | Path | None = None) -> Catalog:
    """Load a catalog file (default: the packaged ``objects.yaml``)."""
    p = Path(path) if path else DEFAULT_CATALOG_PATH
    return _load_cached(str(p.resolve()))


@functools.lru_cache(maxsize=8)
def _load_cached(path: str) -> Catalog:
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
    return Catalog.model_validate(data)
