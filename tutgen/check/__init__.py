"""Answer checking: mark answers files against the results tutgen derives for a spec.

``tutgen check SPEC ANSWERS...`` derives the spec once (:func:`load_reference`), reads each answers
file (:mod:`tutgen.check.answers`) in a bounded child process (:mod:`tutgen.check.run`,
:mod:`tutgen.check.limits`), compares it entry by entry (:mod:`tutgen.check.compare`, by the decision
procedure of :mod:`tutgen.check.equivalence`) with the instructor's marking key
(:mod:`tutgen.check.key`) and reports (:mod:`tutgen.check.report`). The answers format, the decision
procedure, the verdicts and the limits are documented in docs/check.md.
"""

from __future__ import annotations

import sys
import types
from typing import Any

from tutgen.check.answers import AnswerSheet, Tolerance, read_answers
from tutgen.check.compare import EntryResult, ItemResult, Reference, Status, check_sheet
from tutgen.check.key import MarkingKey, read_key
from tutgen.check.run import CheckRun, FileResult, check, load_reference, mark_file, mark_files

__all__ = [
    "AnswerSheet",
    "CheckRun",
    "EntryResult",
    "FileResult",
    "ItemResult",
    "MarkingKey",
    "Reference",
    "Status",
    "Tolerance",
    "check",
    "check_sheet",
    "load_reference",
    "mark_file",
    "mark_files",
    "read_answers",
    "read_key",
]


class _CheckModule(types.ModuleType):
    """The package is also the API function ``tutgen.check(spec, answers, **options)``
    (:func:`tutgen.api.check`): a function and a subpackage of one name cannot both be attributes of
    ``tutgen`` (importing the subpackage rebinds the name), so the subpackage is made callable."""

    def __call__(self, *args: Any, **kwargs: Any) -> CheckRun:
        return check(*args, **kwargs)  # tutgen.check.run.check, as tutgen.api.check


sys.modules[__name__].__class__ = _CheckModule
