"""Can this source physically go on / in this target? Rules on catalog sizes.

Used by spec validation (an impossible task is rejected with its reason), by
the compiler and by the random scene sampler.
"""

from __future__ import annotations

from ladev_lib.catalog import CatalogObject

CONTAINER_WALL_M = 0.01
"""Wall thickness assumed when turning a container's outer size into its opening."""


def _horizontal(obj: CatalogObject) -> tuple[float, float]:
    x, y, _ = obj.size_m
    return (min(x, y), max(x, y))


PLACEMENT_TOLERANCE_M = 0.01
"""How far from the centre of a support a careful placement may land."""
MAX_OVERHANG = 3.0
"""A balanced object may be at most this many times as wide as the top it rests on."""


def fits_on(source: CatalogObject, target: CatalogObject, strict: bool = True) -> str | None:
    """None if ``source`` can rest on ``target``, else why not.

    ``strict`` (random scenes): the target is about as wide as the source. Not
    strict (a task a person names): the source may balance on a smaller top, as a
    can stands on a cube: it stays when its centre of mass lands over the top,
    i.e. when the top's half width covers the placement tolerance, and it may
    overhang the top by up to ``MAX_OVERHANG`` times the top's width. The
    episode's solvability check, not this rule, proves the scene.
    """
    if not target.support:
        return f"{target.display_name!r} cannot hold objects on top"
    s_min, _ = _horizontal(source)
    t_min, _ = _horizontal(target)
    if strict:
        too_small = t_min < 0.9 * s_min
    else:
        too_small = t_min < 2 * PLACEMENT_TOLERANCE_M or s_min > MAX_OVERHANG * t_min
    if too_small:
        return (
            f"{target.display_name!r} ({t_min * 100:.1f} cm across) is too small to hold "
            f"{source.display_name!r} ({s_min * 100:.1f} cm across)"
        )
    return None


def fits_in(source: CatalogObject, container: CatalogObject, strict: bool = True) -> str | None:
    """None if ``source`` fits inside ``container``, else why not.

    ``strict``: the source fits lying along the opening (what random scenes are
    drawn with). Not strict: it may also lie across the opening's diagonal, as
    a person placing a named object would put it (a marker in a mug, a banana
    in a bowl); what a description names is checked this way.
    """
    if not container.container:
        return f"{container.display_name!r} is not a container"
    if not strict:
        return _fits_in_by_hand(source, container)
    s_min, s_max = _horizontal(source)
    c_min, c_max = (v - 2 * CONTAINER_WALL_M for v in _horizontal(container))
    reach = c_max + 0.02
    if s_min + 0.005 > c_min or s_max > reach:
        return (
            f"{source.display_name!r} ({s_min * 100:.1f} x {s_max * 100:.1f} cm) does not fit in "
            f"{container.display_name!r} (opening about {c_min * 100:.1f} x {c_max * 100:.1f} cm)"
        )
    # Standing inside, the source's centre of mass must end below the rim.
    s_height, c_height = source.size_m[2], container.size_m[2]
    if s_height > 2 * c_height:
        return (
            f"{source.display_name!r} ({s_height * 100:.1f} cm tall) would stand far above the rim of "
            f"{container.display_name!r} ({c_height * 100:.1f} cm deep)"
        )
    return None


def _fits_in_by_hand(source: CatalogObject, container: CatalogObject) -> str | None:
    """Whether a person could put ``source`` in ``container``: lying in it (also across the
    diagonal), or standing / leaning in it with at most its upper part above the rim (a spoon
    in a mug). Thinner walls than the strict rule and no clearance: the episode's solvability
    check, not this rule, proves the scene."""
    wall = CONTAINER_WALL_M / 2
    s_min, s_max = _horizontal(source)
    c_min, c_max = (v - 2 * wall for v in _horizontal(container))
    diagonal = (c_min**2 + c_max**2) ** 0.5
    c_height = container.size_m[2]
    thin, mid, long_ = sorted(source.size_m)
    lying = s_min <= c_min and s_max <= max(c_max + 0.02, diagonal) and source.size_m[2] <= 2 * c_height
    leaning = thin <= c_min and mid <= c_max and long_ <= diagonal + c_height
    if lying or leaning:
        return None
    return (
        f"{source.display_name!r} ({s_min * 100:.1f} x {s_max * 100:.1f} cm) does not fit in "
        f"{container.display_name!r} (opening about {c_min * 100:.1f} x {c_max * 100:.1f} cm)"
    )


def task_feasibility(
    task: str, source: CatalogObject, target: CatalogObject | None, strict: bool = True
) -> str | None:
    """None if the task can be done with these objects, else why not (``strict``: see :func:`fits_in`)."""
    if not source.graspable:
        return f"{source.display_name!r} is not graspable"
    if task == "put_on" and target is not None:
        return fits_on(source, target, strict)
    if task == "put_in" and target is not None:
        return fits_in(source, target, strict)
    return None
