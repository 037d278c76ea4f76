"""xacro files as an input: expanded (in robodesc's sandbox unless trusted), then read as URDF."""

from __future__ import annotations

import os

from robodesc.frontends.contract import Frontend, named_robot, xml_root
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def read_xacro(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.packages import PackageResolver
    from robodesc.frontends.urdf import read_urdf_string
    from robodesc.frontends.xacro_expand import expand_xacro

    resolver = PackageResolver(explicit=dict(options.package_paths), input_file=path)
    text = expand_xacro(
        path, options.xacro_args, resolver, findings, trust=options.trust_xacro, allowed_env=options.allowed_env
    )
    return read_urdf_string(
        text,
        file=f"{path} (expanded)",
        base_dir=os.path.dirname(os.path.abspath(path)),
        options=options,
        resolver=resolver,
        findings=findings,
    )


FRONTEND = Frontend(
    name="xacro",
    label="xacro (.xacro, .urdf.xacro)",
    suffixes=(".urdf.xacro", ".xacro"),
    read=read_xacro,
    sniff=lambda head: xml_root(head) == "robot" and "xacro" in head,
    discover=named_robot,
)
