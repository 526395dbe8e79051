"""The object database: SimplerEnv's objects and the YCB objects, as data."""

from ladev_lib.catalog.catalog import (
    Catalog,
    CatalogObject,
    MeshRef,
    load_catalog,
)

__all__ = ["Catalog", "CatalogObject", "MeshRef", "load_catalog"]
