"""A sheet's output paths are planned before anything is written: names that collide on some file
system, or that a file system cannot hold, are refused up front."""

from __future__ import annotations

import pytest

from tutgen.errors import UsageError
from tutgen.sheet.run import check_names


@pytest.mark.parametrize(
    ("names", "expected"),
    [
        pytest.param(["variants/Ada/q.md", "variants/ADA/q.md"], "the same file where case does not count", id="case"),
        pytest.param(
            ["variants/index.csv", "variants/index.csv/q.md"], "as a file and as the directory", id="file-dir"
        ),
        pytest.param(
            ["variants/Index.CSV/q.md", "variants/index.csv"], "as a file and as the directory", id="file-dir-case"
        ),
        pytest.param(["specs/CON.yaml"], "Windows device 'CON.yaml'", id="device"),
        pytest.param(["specs/aux"], "Windows device 'aux'", id="device-bare"),
        pytest.param(["variants/a./q.md"], "ending in a dot or a space", id="dot"),
        pytest.param(["x" * 256], "longer than 255 bytes", id="long"),
        pytest.param(["q.md", "q.md"], "one file twice", id="twice"),
    ],
)
def test_sheet_paths_that_collide_or_cannot_exist_are_refused(names: list[str], expected: str) -> None:
    with pytest.raises(UsageError, match=expected):
        check_names(names)


def test_sheet_paths_that_are_distinct_everywhere_pass() -> None:
    check_names(["questions.md", "variants/A1/questions.md", "variants/A2/questions.md", "variants/index.csv",
                 "variants/console/q.md", "variants/com10/q.md"])  # fmt: skip
