"""The LMS files of a sheet: called once by the sheet's build with every variant's questions."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from tutgen.lms.questions import LmsQuestion


def lms_files(
    title: str, questions: Sequence[LmsQuestion], formats: Sequence[str], names: Mapping[str, str]
) -> tuple[list[tuple[str, str | bytes]], list[str]]:
    """``(file name, content)`` of each LMS export in ``formats`` ("moodle", "qti"; file names from
    ``names``), and the notes naming what an export had to leave out."""
    from tutgen.lms.moodle import moodle_xml
    from tutgen.lms.qti import qti_package

    files: list[tuple[str, str | bytes]] = []
    notes: list[str] = []
    for fmt in formats:
        if fmt == "moodle":
            files.append((names[fmt], moodle_xml(title, questions)))
        elif fmt == "qti":
            package, left = qti_package(title, questions)
            files.append((names[fmt], package))
            notes += left
    return files, notes
