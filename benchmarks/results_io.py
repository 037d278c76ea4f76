"""What every benchmark does with its results: print the table, and write the rows (JSON) and the
table (Markdown) where the command line asks (``--json``, ``--md``)."""

from __future__ import annotations

import json
from typing import Any


def publish(text: str, rows: Any, json_path: str | None, md_path: str | None) -> None:
    print(text)
    if json_path:
        with open(json_path, "w", encoding="utf-8") as handle:
            json.dump(rows, handle, indent=1)
    if md_path:
        with open(md_path, "w", encoding="utf-8") as handle:
            handle.write(text)
