"""The round trip's helpers: write a build to disk, mark the answers read back out of its exports.

The marking is the check's own (``load_reference`` and ``mark_file``, what ``tutgen check`` runs in
each file's process), one derivation per problem and variant. QTI carries only the numeric parts, so
its answers are marked with the variant's key restricted to the items the package holds.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import yaml

from tutgen.lms.readback import moodle_answers, qti_answers


def write_tree(files: dict[str, Any], out: Path) -> None:
    for name, content in files.items():
        if name == "notes":
            continue
        path = out / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))


def left_out(notes: list[str]) -> dict[str, set[str]]:
    """Problem -> the top-level result keys of the parts QTI left out (from the export's notes)."""
    out: dict[str, set[str]] = {}
    for note in notes:
        problem = note.split("left out of ")[1].split(" ")[0]
        labels = note.split("): ", 1)[1].split(", ")
        out[problem] = {label.split(".")[0].split("[")[0] for label in labels}
    return out


def mark(out: Path, files: dict[str, Any]) -> list[tuple[str, str, str]]:
    """(export, question, status) of every question of both exports, marked by the check."""
    from tutgen.check.key import read_key
    from tutgen.check.run import load_reference, mark_file, marking_for

    moodle = moodle_answers(files["questions-moodle.xml"])
    qti = qti_answers(files["questions-qti.zip"])
    missing = left_out(files["notes"])
    results = []
    for ident, answers in moodle.items():
        problem, variant = ident.split("--")
        spec = out / "variants" / variant / "specs" / f"{problem}.yaml"
        key = out / "variants" / variant / f"marking-{problem}.yaml"
        ref = load_reference(spec, key=key)
        path = out / f"moodle-{ident}.yaml"
        path.write_text(yaml.safe_dump(answers, sort_keys=False), encoding="utf-8")
        results.append(("moodle", ident, mark_file(ref, path).status))
        if ident in qti:
            marking = yaml.safe_load(key.read_text(encoding="utf-8"))
            marking["ask"] = [k for k in marking["ask"] if k not in missing.get(problem, set())]
            assert marking["ask"], f"{ident}: a QTI item without a whole graded result"
            qkey = out / f"qti-key-{ident}.yaml"
            qkey.write_text(yaml.safe_dump(marking), encoding="utf-8")
            qref = dataclasses.replace(ref, key=marking_for(ref, read_key(qkey)))
            qpath = out / f"qti-{ident}.yaml"
            qpath.write_text(yaml.safe_dump(qti[ident], sort_keys=False), encoding="utf-8")
            results.append(("qti", ident, mark_file(qref, qpath).status))
    return results
