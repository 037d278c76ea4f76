"""Import robodesc's Isaac-flavoured URDF with Isaac Sim 6.2's own URDF importer.

Runs inside the Isaac Sim consumer environment (Python 3.12, ``isaacsim-asset-isolated``: the
importer without Kit or a GPU). The importer is configured from the ``isaac_sim_6_importer``
section of the ``importer_settings.json`` robodesc wrote beside the URDF, so the settings document
is exercised against the real ``URDFImporterConfig``. Writes one JSON object to ``--out``:

    {"status": "pass" | "fail: <why>", "usd": <the imported asset's .usda>, "seconds": ...}

The imported asset keeps its physics in a ``Physics`` variant set; the Newton check selects
``physx`` (see newton_check.py ``--variant``).
"""

from __future__ import annotations

import argparse
import json
import os
import time
import traceback


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--urdf", required=True, help="the Isaac-flavoured URDF of robodesc's --isaac-sim folder")
    ap.add_argument("--settings", required=True, help="that folder's importer_settings.json")
    ap.add_argument("--out-dir", required=True, help="where the importer writes its asset folder")
    ap.add_argument("--out", required=True, help="the JSON result")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    result: dict[str, object]
    try:
        from isaacsim.asset.importer.urdf import URDFImporter, URDFImporterConfig

        with open(args.settings, encoding="utf-8") as f:
            section = json.load(f)["isaac_sim_6_importer"]
        config = URDFImporterConfig(
            urdf_path=os.path.abspath(args.urdf), usd_path=os.path.abspath(args.out_dir), **section
        )
        path = URDFImporter(config).import_urdf()
        if not path or not os.path.isfile(path):
            result = {"status": f"fail: the importer returned {path!r}", "usd": None}
        else:
            result = {"status": "pass", "usd": os.path.abspath(path)}
    except Exception as exc:
        result = {
            "status": f"fail: {type(exc).__name__}: {str(exc)[:300]}",
            "usd": None,
            "traceback": traceback.format_exc()[-2000:],
        }
    result["seconds"] = round(time.perf_counter() - start, 2)
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(json.dumps(result) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
