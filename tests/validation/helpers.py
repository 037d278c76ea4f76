"""Shared pieces of the validation tests: load a corpus robot, emit it, corrupt the text."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.ir.model import Robot
from robodesc.validation.corpora import CorpusRobot, all_robots

ROOT = Path(__file__).resolve().parents[2]
CORPUS = (ROOT / ".." / "shared" / "corpus").resolve()
SPIRIT_XACRO = CORPUS / "quadsdk/spirit_description/models/spirit/urdf/spirit.urdf.xacro"


@dataclass
class Emitted:
    robot: Robot
    text: str
    base_dir: str


def corpus_robot(name: str, shared_corpus: str) -> CorpusRobot | None:
    for robot in all_robots(shared_corpus):
        if robot.name == name:
            return robot
    return None


def load_and_emit(path: str, packages: dict[str, str] | None = None) -> Emitted:
    loaded = load_path(path, LoadOptions(package_paths=packages or {}))
    base = os.path.dirname(os.path.abspath(path))
    text = emit_urdf(loaded.robot, UrdfOptions(path_mode=PathMode.ABSOLUTE, out_dir=base))
    return Emitted(loaded.robot, text, base)


def edit(text: str, change: Callable[[etree._Element], None]) -> str:
    root = etree.fromstring(text.encode("utf-8"))
    change(root)
    return etree.tostring(root, encoding="unicode")


def joint_el(root: etree._Element, name: str) -> etree._Element:
    found = root.find(f"joint[@name='{name}']")
    assert found is not None, name
    return found


def link_el(root: etree._Element, name: str) -> etree._Element:
    found = root.find(f"link[@name='{name}']")
    assert found is not None, name
    return found
