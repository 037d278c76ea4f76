"""Inputs (files, folders, manifests) and sweeps -> the list of jobs, in a fixed order."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

from robodesc.batch import sweep as sweeps
from robodesc.batch.discover import discover
from robodesc.batch.jobs import Job, check_target, finalize, for_target, robot_stem, with_overrides
from robodesc.batch.manifest import is_manifest, read_manifest
from robodesc.frontends.load import describe_inputs
from robodesc.ir.diagnostics import ConfigError
from robodesc.options import CompileOptions


def _variants(base: Job, spec: Mapping[str, Any] | None, where: str, overrides: Mapping[str, Any]) -> list[Job]:
    if not spec:
        return [base]
    points = sweeps.expand(spec, where)
    width = len(str(len(points)))
    out = []
    for index, point in enumerate(points, start=1):
        values = dict(overrides)
        values["xacro_args"] = {**dict(values.get("xacro_args") or {}), **point}
        out.append(
            Job(
                id=f"{base.id}-v{index:0{width}d}",
                input=base.input,
                path=base.path,
                target=base.target,
                output="",
                options=with_overrides(for_target(base.options, base.target), base.target, values, where),
                variant=point,
            )
        )
    return out


def plan(
    inputs: Sequence[str],
    *,
    target: str,
    options: CompileOptions,
    root: str,
    sweep: Mapping[str, Any] | None = None,
    suffix: str | None = None,
    run_python: bool = False,
    skipped: list[tuple[str, str]] | None = None,
) -> list[Job]:
    """Every job the inputs stand for. A CLI ``sweep`` applies to every input that is not a
    manifest (a manifest row carries its own). ``skipped`` collects the files of a folder that are
    not jobs, and why (:func:`robodesc.batch.discover.discover`)."""
    check_target(target, "--target")
    jobs: list[Job] = []

    def add(path: str, job_id: str, where: str, target_: str, values: Mapping[str, Any], spec: Any, out: str) -> None:
        check_target(target_, where)
        job = Job(
            id=job_id,
            input=path,
            path=os.path.abspath(path),
            target=target_,
            output=out,
            options=with_overrides(for_target(options, target_), target_, values, where),
        )
        jobs.extend(_variants(job, spec, where, values))

    for given in inputs:
        if os.path.isdir(given):
            found = discover(given, run_python=run_python, skipped=skipped)
            if not found:
                hint = "" if run_python else " (Python compositions run when read: --run-python includes them)"
                raise ConfigError(f"{given}: no robot files found ({describe_inputs()}){hint}")
            for path, job_id in found:
                add(path, job_id, path, target, {}, sweep, "")
        elif not os.path.isfile(given):
            raise ConfigError(f"{given}: no such file or folder")
        elif is_manifest(given):
            for row in read_manifest(given):
                if not os.path.isfile(row.input):
                    raise ConfigError(f"{row.where}: input {row.input!r}: no such file")
                out = os.path.join(os.path.abspath(root), row.output) if row.output else ""
                add(
                    row.input,
                    row.id or robot_stem(row.input),
                    row.where,
                    row.target or target,
                    row.options,
                    row.sweep,
                    out,
                )
        else:
            add(given, robot_stem(given), given, target, {}, sweep, "")
    return finalize(jobs, root, suffix)
