"""How many corpus robots carry Gazebo contact parameters, which ones, and what each target writes.

    python benchmarks/contact_survey.py            # the 100-robot test corpus (robodesc.validation.corpora)
    python benchmarks/contact_survey.py --json out.json --md out.md

Reads each robot with default flags (as ``robodesc compile`` would), then counts links and colliders
with contact parameters (``Link.contact``, ``Collision.contact``) by parameter, and compiles each
robot that has any to USD, SDF, MJCF and URDF to count what each writes: USD physics materials and
their bindings, SDF ``<surface>`` elements, MJCF collision geoms with a ``friction`` / ``solref`` of
their own, URDF ``<gazebo reference>`` blocks kept; and each target's "not representable" warnings.
Results: benchmarks/results/contact_survey.md and .json.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections import Counter
from typing import Any

from results_io import publish

import robodesc
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.validation.corpora import all_robots


def _lost(result: Any) -> list[str]:
    return sorted(
        {f.message.split(";")[0].split(":")[0] for f in result.findings if f.code == "contact-not-representable"}
    )


def survey(robot_entry: Any) -> dict[str, Any] | None:
    try:
        robot = load_path(
            robot_entry.path, LoadOptions(package_paths=robot_entry.packages, xacro_args=robot_entry.xacro_args)
        ).robot
    except Exception as exc:  # a corpus robot robodesc refuses is counted, not fatal
        return {"robot": robot_entry.name, "error": str(exc).splitlines()[0][:120]}
    params: Counter[str] = Counter()
    links = 0
    for link in robot.links:
        found = [link.contact] + [c.contact for c in link.collisions]
        found = [c for c in found if c is not None]
        if found:
            links += 1
        for contact in found:
            params.update(contact.given().keys())
    row: dict[str, Any] = {"robot": robot_entry.name, "links_with_contact": links, "parameters": dict(params)}
    if links:
        with tempfile.TemporaryDirectory() as tmp:
            opts = {"package_paths": robot_entry.packages, "xacro_args": robot_entry.xacro_args, "validate": False}
            usd = robodesc.compile_to_usd(robot_entry.path, os.path.join(tmp, "r.usda"), **opts)
            sdf = robodesc.compile_to_sdf(robot_entry.path, os.path.join(tmp, "r.sdf"), **opts)
            mjcf = robodesc.compile_to_mjcf(robot_entry.path, os.path.join(tmp, "r.xml"), **opts)
            urdf = robodesc.compile_to_urdf(robot_entry.path, **opts)
            with open(usd.files["usd"], encoding="utf-8") as handle:
                text = handle.read()
            row["usd_materials"] = text.count('def Material "contact')
            row["usd_bindings"] = text.count("material:binding:physics")
            row["sdf_surfaces"] = (sdf.text or "").count("<surface>")
            geoms = ET.parse(mjcf.files["mjcf"]).getroot().iter("geom")
            own = [g for g in geoms if g.get("friction") is not None or g.get("solref") is not None]
            row["mjcf_geoms"] = len(own)
            row["mjcf_solref"] = sum(1 for g in own if g.get("solref") is not None)
            # Parsed, not counted as text: the writer may wrap or reorder a block's attributes.
            tree = ET.fromstring(urdf.text) if urdf.text else ET.Element("robot")
            row["urdf_gazebo_blocks"] = sum(1 for g in tree.iter("gazebo") if g.get("reference"))
            row["urdf_surfaces"] = sum(1 for c in tree.iter("collision") for _ in c.iter("surface"))
            row["not_representable"] = _lost(usd)
            row["mjcf_not_representable"] = _lost(mjcf)
    return row


def markdown(rows: list[dict[str, Any]]) -> str:
    with_contact = [r for r in rows if r.get("links_with_contact")]
    total = {k: sum(r.get(k, 0) for r in with_contact) for k in ("usd_bindings", "sdf_surfaces", "mjcf_geoms")}
    refused = [r for r in rows if "error" in r]
    lines = [
        "# Gazebo contact parameters on the corpus, and what each target writes",
        "",
        "`python benchmarks/contact_survey.py --json benchmarks/results/contact_survey.json --md "
        "benchmarks/results/contact_survey.md` (default flags).",
        "",
        f"**{len(rows)} robots read** ({len(refused)} refused by the loader), **{len(with_contact)} carry Gazebo "
        f"contact parameters**. Their colliders: USD binds a physics material to {total['usd_bindings']}, SDF "
        f"writes {total['sdf_surfaces']} `<surface>`, MJCF gives {total['mjcf_geoms']} collision geoms their own "
        "`friction` (and `solref` where kp is given); URDF keeps every `<gazebo reference>` block (all of a "
        "robot's, not only contact ones) and every `<surface>` inside a `<collision>` (Stretch's, Spirit's) "
        "as it came.",
        "",
        "| robot | links | parameters | USD materials / bound colliders | SDF `<surface>` | MJCF geoms (with solref) "
        "| URDF `<gazebo reference>` blocks / collision `<surface>` written | not in USD | not in MJCF |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in with_contact:
        params = ", ".join(f"{k} {v}" for k, v in sorted(r["parameters"].items()))
        lines.append(
            f"| {r['robot']} | {r['links_with_contact']} | {params} | {r['usd_materials']} / {r['usd_bindings']} | "
            f"{r['sdf_surfaces']} | {r['mjcf_geoms']} ({r['mjcf_solref']}) | {r['urdf_gazebo_blocks']} / {r['urdf_surfaces']} | "
            f"{'; '.join(r['not_representable']) or '–'} | {'; '.join(r['mjcf_not_representable']) or '–'} |"
        )
    if refused:
        lines += ["", "Refused: " + "; ".join(f"{r['robot']} ({r['error']})" for r in refused)]
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", help="also write every row")
    parser.add_argument("--md", help="also write the table")
    args = parser.parse_args()
    shared = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "corpus")
    rows = [r for r in (survey(e) for e in all_robots(shared)) if r is not None]
    publish(markdown(rows), rows, args.json, args.md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
