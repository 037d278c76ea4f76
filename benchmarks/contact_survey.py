"""How many corpus robots carry Gazebo contact parameters, which ones, and what each target writes.

    python benchmarks/contact_survey.py            # the 100-robot test corpus (robodesc.validation.corpora)
    python benchmarks/contact_survey.py --json out.json

Reads each robot with default flags (as ``robodesc compile`` would), then counts links and colliders
with contact parameters (``Link.contact``, ``Collision.contact``) by parameter, and compiles each
robot that has any to USD and SDF to count the physics materials and ``<surface>`` elements written.
Results: benchmarks/results/contact_survey.md.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from collections import Counter
from typing import Any

import robodesc
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.validation.corpora import all_robots


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
            with open(usd.files["usd"], encoding="utf-8") as handle:
                text = handle.read()
            row["usd_materials"] = text.count('def Material "contact')
            row["usd_bindings"] = text.count("material:binding:physics")
            row["sdf_surfaces"] = (sdf.text or "").count("<surface>")
            row["not_representable"] = sorted(
                {f.message.split(";")[0] for f in usd.findings if f.code == "contact-not-representable"}
            )
    return row


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", help="also write every row")
    args = parser.parse_args()
    shared = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "corpus")
    rows = [r for r in (survey(e) for e in all_robots(shared)) if r is not None]
    with_contact = [r for r in rows if r.get("links_with_contact")]
    print(f"{len(rows)} robots read; {len(with_contact)} carry Gazebo contact parameters")
    for r in with_contact:
        print(
            f"  {r['robot']}: {r['links_with_contact']} links, parameters {r['parameters']}; USD "
            f"{r['usd_materials']} material(s) bound to {r['usd_bindings']} collider(s); SDF {r['sdf_surfaces']} <surface>"
            + (f"; not in USD: {r['not_representable']}" if r["not_representable"] else "")
        )
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump(rows, handle, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
