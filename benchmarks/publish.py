"""Write a benchmark's results: all the numbers as JSON, the tables as markdown, both whole."""

from __future__ import annotations

import json
from pathlib import Path

from numerics.files import write_text

RESULTS = Path(__file__).resolve().parent / "results"


def publish(name: str, results: dict, markdown: str) -> None:
    """Write ``results/<name>.json`` and ``results/<name>.md`` and print the markdown."""
    write_text(RESULTS / f"{name}.json", json.dumps(results, indent=1) + "\n")
    write_text(RESULTS / f"{name}.md", markdown + "\n")
    print(markdown)
