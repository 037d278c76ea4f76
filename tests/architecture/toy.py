"""A throwaway target and a throwaway frontend, written the way robodesc's own are and registered
from outside the package (``--plugin tests.architecture.toy``): the proof that a new target or input
format needs no driver code.

The frontend reads ``.toy`` files (and ``.xml`` files whose root is ``<toy>``): one ``link NAME MASS``
or ``joint NAME PARENT CHILD`` per line. The target writes the robot as JSON (``.toyjson``); its
check reads the JSON back and compares link names and masses with the IR."""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field

from robodesc._files import write_atomic
from robodesc.emit.common.flags import flag
from robodesc.emit.common.target import CheckRequest, EmitRequest, Emitted, Target
from robodesc.frontends.contract import Frontend, xml_root
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc
from robodesc.ir.geometry import Inertia, Inertial, Pose
from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.validation.report import Status, ValidationReport


# ---- the frontend -------------------------------------------------------------------------------
def read_toy(path: str, options: LoadOptions, findings: Findings) -> Robot:
    robot = Robot(name=os.path.basename(path).split(".")[0], source_file=path)
    with open(path, encoding="utf-8") as handle:
        for number, line in enumerate(handle, 1):
            words = re.sub(r"<[^>]*>", "", line).split()
            if not words:
                continue
            if words[0] == "link" and len(words) == 3:
                mass = float(words[2])
                robot.links.append(Link(name=words[1], inertial=Inertial(mass=mass, inertia=Inertia(mass, mass, mass))))
            elif words[0] == "joint" and len(words) == 4:
                robot.joints.append(
                    Joint(name=words[1], type=JointType.FIXED, parent=words[2], child=words[3], origin=Pose())
                )
            else:
                what = f"expected 'link NAME MASS' or 'joint NAME PARENT CHILD', got {line.strip()!r}"
                raise ParseError(what, loc=SourceLoc(path, number))
    return robot


FRONTEND = Frontend(
    name="toy",
    label="toy robots (.toy)",
    suffixes=(".toy", ".xml"),
    read=read_toy,
    sniff=lambda head: xml_root(head) == "toy",
)


# ---- the target ---------------------------------------------------------------------------------
@dataclass(slots=True)
class ToyOptions:
    indent: int = field(default=0, metadata=flag("JSON indentation", name="--toy-indent", type=int, metavar="N"))


def emit_toy(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    options: ToyOptions = request.options
    doc = {
        "name": robot.name,
        "links": {link.name: link.inertial.mass if link.inertial else None for link in robot.links},
    }
    text = json.dumps(doc, indent=options.indent or None)
    emitted = Emitted(text=text)
    if request.out:
        write_atomic(request.out, text)
        emitted.files["toy"] = request.out
    return emitted


def check_toy(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport:
    report = ValidationReport(robot=robot.name, target="toy", consumer="json")
    links = json.loads(emitted.text or "{}")["links"]
    for link in robot.links:
        ok = link.name in links and links[link.name] == (link.inertial.mass if link.inertial else None)
        report.add("mass", Status.PASS if ok else Status.FAIL, f"link {link.name!r}")
    return report


TARGET = Target(
    name="toy",
    emit=emit_toy,
    summary="a toy JSON target",
    suffixes=(".toyjson",),
    options=ToyOptions,
    stdout=True,
    check=check_toy,
    options_title="toy (-t toy)",
)
