"""Every physics attribute of a USD checked against the schema that defines it.

A USD reader takes only what a registered schema defines: an API schema no package defines, or an
attribute no applied schema declares, is read by nothing (ovstage populates an attribute only when a
registered schema defines it, so PhysX silently drops it). robodesc wrote ``PhysxJointAPI``'s
``physxJoint:*`` for years after PhysX stopped reading it; this check would have said so.

usd-core defines the ``Physics*`` schemas; ``physx-usd-schemas`` (``Physx*``) and
``newton-usd-schemas`` (``Newton*``) are codeless schema packages that register their
``plugInfo.json`` with ``pxr.Plug.Registry`` when imported. The check runs only when both import
(the test extra installs them); otherwise it is one skip row.

Checked: every applied API schema whose family is one of those packages' (``Physics``, ``Physx``,
``Newton``; Isaac Sim's ``Isaac*`` robot schema is not installable here and is counted as unchecked),
and every authored attribute in a physics namespace (``physics:*``, ``physx*``, ``newton:*``, and
the multiple-apply ``drive:<i>:physics:*``, ``limit:<i>:physics:*``, ``state:<i>:physics:*``): its
name must be a property of the prim's composed definition (its type and every registered applied
API, instance names filled in) and its value type the one the schema declares.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from robodesc.validation.report import Status, ValidationReport

CHECK = "usd-schema"
SCHEMA_PACKAGES = ("physx_usd_schemas", "newton_usd_schemas")
# API schema families whose definitions those packages and usd-core hold.
CHECKED_FAMILIES = ("Physics", "Physx", "Newton")
# The legacy single-apply PhysxJointAPI, written on request for Isaac Sim 4.x/5.x (docs/isaac.md).
LEGACY = {"PhysxJointAPI": "the legacy PhysxJointAPI (Isaac Sim 4.x/5.x, --isaac-version); PhysX 25.11 has none"}
# Rows listed one by one before the rest are counted in one line.
MAX_ROWS = 20


@dataclass(slots=True)
class SchemaCensus:
    """What one stage applies and authors, and which of it no registered schema defines."""

    api_schemas: int = 0
    attributes: int = 0
    unchecked: set[str] = field(default_factory=set)
    # (prim path, schema or attribute, why)
    unknown_schemas: list[tuple[str, str, str]] = field(default_factory=list)
    unknown_attributes: list[tuple[str, str, str]] = field(default_factory=list)


def register_schemas() -> list[str]:
    """Import the schema packages (each registers its plugins in usd-core); the versions found, or
    the names that did not import, prefixed with ``missing:``."""
    out = []
    for name in SCHEMA_PACKAGES:
        try:
            module = importlib.import_module(name)
        except ImportError:
            out.append(f"missing:{name}")
            continue
        out.append(f"{name.replace('_', '-')} {getattr(module, '__version__', '?')}")
    return out


def is_physics_attribute(name: str) -> bool:
    if name.startswith(("physics:", "physx", "newton:")):
        return True
    parts = name.split(":")
    return len(parts) >= 4 and parts[0] in ("drive", "limit", "state") and parts[2] == "physics"


def census(stage: Any) -> SchemaCensus:
    """Walk every prim of ``stage`` (instance proxies too) and sort what it applies and authors."""
    from pxr import Usd

    registry = Usd.SchemaRegistry()
    out = SchemaCensus()
    for prim in _prims(stage):
        path = str(prim.GetPath())
        for applied in prim.GetPrimTypeInfo().GetAppliedAPISchemas():
            out.api_schemas += 1
            type_name, _instance = Usd.SchemaRegistry.GetTypeNameAndInstance(applied)
            if registry.FindAppliedAPIPrimDefinition(type_name) is not None:
                continue
            if not type_name.startswith(CHECKED_FAMILIES):
                out.unchecked.add(type_name)
                continue
            why = LEGACY.get(type_name, "no registered schema package defines it: readers ignore it")
            out.unknown_schemas.append((path, applied, why))
        definition = prim.GetPrimDefinition()
        for attr in prim.GetAuthoredAttributes():
            name = attr.GetName()
            if not is_physics_attribute(name):
                continue
            out.attributes += 1
            spec = definition.GetAttributeDefinition(name)
            if not spec:
                why = "no schema applied to the prim defines it"
                if name.startswith("physxJoint:"):
                    why += f" ({LEGACY['PhysxJointAPI']})"
                out.unknown_attributes.append((path, name, why))
                continue
            # usd-core reports a defined attribute's type from its definition: the authored spec says
            # what the file holds (a reader converts or drops a value of another type).
            authored = _authored_type(attr)
            if authored is not None and authored != spec.GetTypeName():
                out.unknown_attributes.append(
                    (path, name, f"authored as {authored}, the schema declares {spec.GetTypeName()}")
                )
    return out


def _authored_type(attr: Any) -> Any:
    for spec in attr.GetPropertyStack():
        if spec.typeName:
            return spec.typeName
    return None


def _prims(stage: Any) -> Iterator[Any]:
    from pxr import Usd

    yield from stage.Traverse(Usd.TraverseInstanceProxies(Usd.PrimAllPrimsPredicate))


def check_schemas(stage: Any, report: ValidationReport) -> SchemaCensus | None:
    """Add the ``usd-schema`` rows for ``stage`` to ``report``: one warning per unknown schema or
    attribute (up to :data:`MAX_ROWS`, then a count), else one pass row; a skip row without the
    schema packages. Registration must precede opening the stage (:func:`register_schemas`)."""
    found = register_schemas()
    missing = [name[len("missing:") :] for name in found if name.startswith("missing:")]
    if missing:
        report.add(
            CHECK,
            Status.SKIP,
            "document",
            f"skipped: {', '.join(missing)} not installed (pip install physx-usd-schemas newton-usd-schemas)",
        )
        return None
    report.info[CHECK] = ", ".join(found)
    seen = census(stage)
    problems = [("API schema", *row) for row in seen.unknown_schemas]
    problems += [("attribute", *row) for row in seen.unknown_attributes]
    for what, path, name, why in problems[:MAX_ROWS]:
        report.add(CHECK, Status.WARN, path, f"{what} {name}: {why}")
    if len(problems) > MAX_ROWS:
        report.add(CHECK, Status.WARN, "document", f"{len(problems) - MAX_ROWS} more unknown schemas or attributes")
    unchecked = f"; not checked (schema not installed): {', '.join(sorted(seen.unchecked))}" if seen.unchecked else ""
    if not problems:
        report.add(
            CHECK,
            Status.PASS,
            "document",
            f"{seen.api_schemas} applied API schemas and {seen.attributes} physics attributes, each defined by "
            f"usd-core, {', '.join(found)}{unchecked}",
        )
    elif unchecked:
        report.add(CHECK, Status.SKIP, "document", unchecked[2:])
    return seen
